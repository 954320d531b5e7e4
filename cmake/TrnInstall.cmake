# `cmake --install` gives headers, the layer libraries (libtrnkit_core.so ...), the trnkit CLI
# (RUNPATH $ORIGIN/../lib), trnkitConfig.cmake with trnkit::core ... trnkit::experiments and
# trnkit::trnkit (all of them), and trnkit.pc (the core, for pkg-config and plain compiler calls).
# Implementation dependencies are private to the shared libraries, so a consumer needs nothing else;
# the targets carry cxx_std_20.
include(CMakePackageConfigHelpers)
get_property(TRN_LAYER_TARGETS GLOBAL PROPERTY TRN_LAYERS)
install(TARGETS ${TRN_LAYER_TARGETS} trnkit EXPORT trnkitTargets
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

# pkg-config: relocatable (paths relative to the .pc file), so the install prefix may move.
file(RELATIVE_PATH TRN_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" TRN_PC_TO_PREFIX "${TRN_PC_TO_PREFIX}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/trnkit.pc.in ${CMAKE_CURRENT_BINARY_DIR}/trnkit.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/trnkit.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
