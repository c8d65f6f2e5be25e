# `cmake --install BUILD --component runtime` installs the torch-free runtime for other programs:
# include/mimic/runtime.hpp, the static libraries below it (control, env, sim, motion, core) and a
# package config, so that find_package(mimic) gives mimic::runtime (examples/embed). The runtime's
# own dependencies are found again by the package config; LibTorch is not one of them.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS mimic_control mimic_env mimic_sim mimic_motion mimic_core mimic_mujoco mimic_warnings
  EXPORT mimicTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/mimic DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT runtime)
install(EXPORT mimicTargets NAMESPACE mimic:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mimic COMPONENT runtime)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/mimicConfig.cmake.in ${PROJECT_BINARY_DIR}/mimicConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mimic)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/mimicConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/mimicConfig.cmake ${PROJECT_BINARY_DIR}/mimicConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mimic COMPONENT runtime)
