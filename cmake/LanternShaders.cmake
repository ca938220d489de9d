# GLSL -> SPIR-V at build time with glslangValidator. Each shader writes a depfile, so editing an
# included header (e.g. shaders/shared/*.h) rebuilds exactly its dependants.
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)
# PNanoVDB.h (libnanovdb-dev) compiles as GLSL: the volume lookup benchmark's kernel includes it.
find_path(LANTERN_NANOVDB_INCLUDE_DIR nanovdb/PNanoVDB.h REQUIRED)
set(LANTERN_SHADER_OUTPUT_DIR ${CMAKE_BINARY_DIR}/shaders)
set(LANTERN_SHADER_TARGET_ENV vulkan1.2)

# lantern_compile_shader(<source> <variant> [DEFINES ...]) appends the .spv to LANTERN_SPIRV_FILES.
# variant "" is the default build; otherwise the output is <name>.<variant>.spv.
function(lantern_compile_shader source variant)
  cmake_parse_arguments(ARG "" "" "DEFINES" ${ARGN})
  file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR}/shaders ${source})
  if(variant STREQUAL "")
    set(out ${LANTERN_SHADER_OUTPUT_DIR}/${rel}.spv)
  else()
    set(out ${LANTERN_SHADER_OUTPUT_DIR}/${rel}.${variant}.spv)
  endif()
  set(defines "")
  foreach(d IN LISTS ARG_DEFINES)
    list(APPEND defines -D${d})
  endforeach()
  get_filename_component(out_dir ${out} DIRECTORY)
  add_custom_command(OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${out_dir}
    COMMAND ${GLSLANG_VALIDATOR} --quiet --target-env ${LANTERN_SHADER_TARGET_ENV}
            -I${PROJECT_SOURCE_DIR}/shaders -I${LANTERN_NANOVDB_INCLUDE_DIR} ${defines}
            --depfile ${out}.d -o ${out} ${source}
    DEPENDS ${source}
    DEPFILE ${out}.d
    COMMENT "glslang ${rel} ${variant}"
    VERBATIM)
  set_property(GLOBAL APPEND PROPERTY LANTERN_SPIRV_FILES ${out})
  set_property(GLOBAL APPEND PROPERTY LANTERN_SHADER_MANIFEST "${rel}|${variant}|${ARG_DEFINES}")
endfunction()
