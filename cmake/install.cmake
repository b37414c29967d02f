# `cmake --install build --prefix P`: the `lutex` executable in P/bin, the static libraries in P/lib, every
# public header under P/include/lutex/ (same paths as in the tree) and the CMake package lutex::lutex in
# P/lib/cmake/lutex, for C++ projects that embed lutex (tests/install/ builds one against it).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# lutex::lutex: every library layer below the command line.
add_library(lutex_library INTERFACE)
target_link_libraries(lutex_library INTERFACE lutex_core lutex_texturing lutex_colmap_io lutex_stages)
set_target_properties(lutex_library PROPERTIES EXPORT_NAME lutex)
add_library(lutex::lutex ALIAS lutex_library)

install(TARGETS lutex RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS lutex_library lutex_core lutex_texturing lutex_colmap_io lutex_stages lutex_warnings
        EXPORT lutexTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lutex)
foreach(folder lib texturing colmap_integration/io colmap_integration/stages)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lutex/${folder}
          FILES_MATCHING PATTERN "*.h")
endforeach()

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/lutex)
install(EXPORT lutexTargets NAMESPACE lutex:: DESTINATION ${config_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/lutexConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/lutexConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/lutexConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/lutexConfig.cmake ${PROJECT_BINARY_DIR}/lutexConfigVersion.cmake
        DESTINATION ${config_dir})
