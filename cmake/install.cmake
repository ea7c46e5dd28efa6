# `cmake --install build --prefix P`: the CLI, the public headers, the core library (static and
# shared with a SONAME), the scenes, a CMake package (find_package(dampbound CONFIG) ->
# dampbound::core), a pkg-config file and the man page. Everything is relative to the prefix
# chosen at install time (the package files are relocatable).
include(CMakePackageConfigHelpers)

install(TARGETS dampbound RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS dampbound_core dampbound_core_shared EXPORT dampboundTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} NAMELINK_COMPONENT Development
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
set_target_properties(dampbound_core PROPERTIES EXPORT_NAME core_static)
set_target_properties(dampbound_core_shared PROPERTIES EXPORT_NAME core)
install(EXPORT dampboundTargets NAMESPACE dampbound::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/dampbound)

# Public headers: include/dampbound/ as it is in the source tree (the umbrella dampbound.hpp,
# monitor.hpp, physics/, run/, analysis/), and the generated version.hpp beside them. Their own
# `#include "dampbound/..."` lines find each other under the prefix's include/.
install(DIRECTORY include/dampbound DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp")
install(FILES ${PROJECT_BINARY_DIR}/include/dampbound/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/dampbound)

install(DIRECTORY scenes/ DESTINATION ${DAMPBOUND_INSTALL_SCENESDIR})
install(FILES docs/dampbound.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)

configure_package_config_file(cmake/dampboundConfig.cmake.in
  ${PROJECT_BINARY_DIR}/dampboundConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/dampbound
  PATH_VARS DAMPBOUND_INSTALL_SCENESDIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/dampboundConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/dampboundConfig.cmake
              ${PROJECT_BINARY_DIR}/dampboundConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/dampbound)

# pkg-config: the prefix is found from the .pc file's own place, so any --prefix works.
file(RELATIVE_PATH DAMPBOUND_PC_TO_PREFIX
     /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
configure_file(cmake/dampbound.pc.in ${PROJECT_BINARY_DIR}/dampbound.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/dampbound.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
