# `cmake --install build [--prefix DIR]`: the engine, runtime and lighting static libraries, their
# headers (include/lantern/{engine,runtime,lighting,shared}), the compiled SPIR-V and the content
# (share/lantern/{shaders,content}) and a CMake package: find_package(Lantern) gives
# Lantern::lighting (Lantern::runtime, Lantern::engine, Lantern::shared under it) and the variables
# Lantern_SHADER_DIR and Lantern_CONTENT_DIR (installed locations, relative to the prefix, so the
# installed tree can be moved). The `lantern` command and the tests are not installed.
include(CMakePackageConfigHelpers)

set(LANTERN_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/Lantern)
set(LANTERN_INSTALL_SHADERDIR ${CMAKE_INSTALL_DATADIR}/lantern/shaders)
set(LANTERN_INSTALL_CONTENTDIR ${CMAKE_INSTALL_DATADIR}/lantern/content)

set_target_properties(lantern_shared PROPERTIES EXPORT_NAME shared)
set_target_properties(lantern_engine PROPERTIES EXPORT_NAME engine)
set_target_properties(lantern_runtime PROPERTIES EXPORT_NAME runtime)
set_target_properties(lantern_lighting PROPERTIES EXPORT_NAME lighting)
install(TARGETS lantern_shared lantern_engine lantern_runtime lantern_lighting
  EXPORT LanternTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(EXPORT LanternTargets NAMESPACE Lantern:: DESTINATION ${LANTERN_INSTALL_CMAKEDIR})

foreach(layer engine runtime lighting)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${layer} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lantern
    FILES_MATCHING PATTERN "*.h")
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders/shared
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lantern FILES_MATCHING PATTERN "*.h")
# runtime::ShaderLibrary reads <dir>/<relpath>[.variant].spv; manifest.txt lists them.
install(DIRECTORY ${LANTERN_SHADER_OUTPUT_DIR}/ DESTINATION ${LANTERN_INSTALL_SHADERDIR}
  FILES_MATCHING PATTERN "*.spv" PATTERN "manifest.txt" PATTERN "CMakeFiles" EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/content/ DESTINATION ${LANTERN_INSTALL_CONTENTDIR})

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/LanternConfig.cmake.in
  ${CMAKE_BINARY_DIR}/LanternConfig.cmake INSTALL_DESTINATION ${LANTERN_INSTALL_CMAKEDIR}
  PATH_VARS LANTERN_INSTALL_SHADERDIR LANTERN_INSTALL_CONTENTDIR)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/LanternConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/LanternConfig.cmake ${CMAKE_BINARY_DIR}/LanternConfigVersion.cmake
  DESTINATION ${LANTERN_INSTALL_CMAKEDIR})
