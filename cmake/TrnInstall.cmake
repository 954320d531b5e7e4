# `cmake --install` gives headers, libtrnkit and trnkitConfig.cmake so that another project can
# find_package(trnkit) and link trnkit::trnkit. Dependencies are private to the shared library,
# so a consumer needs nothing else.
include(CMakePackageConfigHelpers)
install(TARGETS trnkit EXPORT trnkitTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT trnkitTargets NAMESPACE trnkit:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/trnkit)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/trnkitConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/trnkitConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/trnkit)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/trnkitConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/trnkitConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/trnkitConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/trnkit)
