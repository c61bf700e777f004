# Installs the CMake package so other codes can find_package(blastsim) and link blastsim::cip etc.
include(CMakePackageConfigHelpers)
set(BLASTSIM_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/blastsim)
install(EXPORT blastsimTargets NAMESPACE blastsim:: DESTINATION ${BLASTSIM_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/blastsimConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/blastsimConfig.cmake INSTALL_DESTINATION ${BLASTSIM_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/blastsimConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/blastsimConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/blastsimConfigVersion.cmake
  DESTINATION ${BLASTSIM_CMAKE_DIR})
