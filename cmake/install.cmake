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

# Public headers: include/dampbound/monitor.hpp and version.hpp at the top, and the core
# headers they (and a Session) need under include/dampbound/core/, where their own
# `#include "core/..."` lines find each other.
install(FILES core/monitor.hpp ${PROJECT_BINARY_DIR}/include/dampbound/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/dampbound)
foreach(header ${DAMPBOUND_PUBLIC_HEADERS})
  get_filename_component(folder ${header} DIRECTORY)
  install(FILES ${PROJECT_SOURCE_DIR}/core/${header}
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/dampbound/core/${folder})
endforeach()

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
