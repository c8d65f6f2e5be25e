# ASan + UBSan for the whole build (tests, fuzz targets and the command) when MIMIC_SANITIZE=ON.
if(MIMIC_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
