# `cmake --install BUILD --prefix P`: the tool (P/bin/motifmine, and P/bin/motifmine-mpi where MPI
# was found), the library (P/lib/libmotifmine.so)
# with its headers (P/include/motifmine/) and a CMake package, so that a downstream project
# configured with -DCMAKE_PREFIX_PATH=P does find_package(motifmine CONFIG REQUIRED) and links
# motifmine::motifmine (examples/mine_archive; docs/library.md).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(MOTIF_PACKAGE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/motifmine)
install(TARGETS motifmine RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET motifmine-mpi)  # built where MPI is found (engine/CMakeLists.txt)
  install(TARGETS motifmine-mpi RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(TARGETS motifmine_library EXPORT motifmineTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/motifmine
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT motifmineTargets NAMESPACE motifmine:: DESTINATION ${MOTIF_PACKAGE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/motifmineConfig.cmake.in
  ${PROJECT_BINARY_DIR}/motifmineConfig.cmake INSTALL_DESTINATION ${MOTIF_PACKAGE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/motifmineConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/motifmineConfig.cmake
              ${PROJECT_BINARY_DIR}/motifmineConfigVersion.cmake
  DESTINATION ${MOTIF_PACKAGE_DIR})
