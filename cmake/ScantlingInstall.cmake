# Install and export the module libraries so that `find_package(scantling)` works downstream.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

get_property(_scantling_targets GLOBAL PROPERTY SCANTLING_MODULE_TARGETS)
install(TARGETS ${_scantling_targets} EXPORT scantlingTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/scantling DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT scantlingTargets NAMESPACE scantling::
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/scantling)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/scantlingConfig.cmake.in
  ${PROJECT_BINARY_DIR}/scantlingConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/scantling)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/scantlingConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
# FindOpenCVImgproc.cmake goes beside the config: Debian's OpenCV has no config of its own,
# and the exported scantling::perception links OpenCV::imgproc.
install(FILES ${PROJECT_BINARY_DIR}/scantlingConfig.cmake
  ${PROJECT_BINARY_DIR}/scantlingConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/FindOpenCVImgproc.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/scantling)
