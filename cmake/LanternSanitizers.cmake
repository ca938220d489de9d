# Sanitizer and fuzzing build configurations (issue 7). Both are off by default; the normal build
# (GCC, Release) is unchanged.
#
#   -DLANTERN_SANITIZE=address,undefined   ASan + UBSan for every target of the tree (GCC or clang).
#                                          scripts/sanitize.sh builds build-asan with it and runs ctest.
#   -DLANTERN_FUZZ=ON                      libFuzzer targets in tests/fuzz (clang only; implies
#                                          -fsanitize=fuzzer-no-link plus LANTERN_SANITIZE).
#                                          scripts/fuzz.sh builds build-fuzz with it.
set(LANTERN_SANITIZE "" CACHE STRING
    "Comma-separated sanitizers for all targets, e.g. address,undefined (empty: none)")
option(LANTERN_FUZZ "Build the libFuzzer targets in tests/fuzz (needs clang)" OFF)

if(LANTERN_FUZZ AND NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "LANTERN_FUZZ=ON needs clang (libFuzzer); use scripts/fuzz.sh")
endif()

if(LANTERN_SANITIZE)
  # Frame pointers for readable stacks; UBSan findings are errors (the run stops at the first one)
  # so ctest cannot pass with a report in the log.
  add_compile_options(-fsanitize=${LANTERN_SANITIZE} -fno-omit-frame-pointer
                      -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${LANTERN_SANITIZE} -fno-sanitize-recover=all)
  if(LANTERN_SANITIZE MATCHES "undefined")
    # UBSan's vptr check references the typeinfo of every polymorphic class it sees; Debian's
    # glslang is built without RTTI (no typeinfo for glslang::TShader: link error), so the one file
    # that uses glslang is built without that check. Set at the end of configuration, once the
    # runtime directory exists.
    cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL set_source_files_properties
      ${CMAKE_SOURCE_DIR}/runtime/gpu/glsl_compiler.cpp DIRECTORY ${CMAKE_SOURCE_DIR}/runtime
      PROPERTIES COMPILE_OPTIONS -fno-sanitize=vptr)
  endif()
  message(STATUS "Lantern: sanitizers ${LANTERN_SANITIZE}")
endif()

if(LANTERN_FUZZ)
  # Instrument everything for coverage; only the fuzz executables link libFuzzer's main.
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
