# ASan + UBSan for the whole build (tests, fuzz targets and the command) when MIMIC_SANITIZE=ON.
if(MIMIC_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
  # Under ASan, Eigen's headers allocate with their own alignment padding (Memory.h checks
  # __SANITIZE_ADDRESS__), while the prebuilt Ceres library inlined Eigen's plain malloc/free: one
  # side freed what the other allocated ("bad-free" in Ceres's sparse Cholesky). glibc's malloc
  # already aligns to the 16 bytes Eigen needs here, so both sides are told to use it.
  add_compile_definitions(EIGEN_MALLOC_ALREADY_ALIGNED=1)
endif()
