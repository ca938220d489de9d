# Warnings for Lantern's own targets (third-party headers are included as SYSTEM by their targets).
function(lantern_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
    -Wcast-align -Wunused -Woverloaded-virtual -Wnull-dereference -Wimplicit-fallthrough
    # Vulkan create-info structs are written with designated initializers that name only the
    # fields that matter; GCC would flag every omitted (zero) field.
    -Wno-missing-field-initializers)
  if(LANTERN_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# A layer library: every .cpp under DIR (recursively), include root = the repository root.
function(lantern_layer target dir)
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${dir}/*.cpp)
  add_library(${target} STATIC ${sources})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/lantern>)
  target_compile_features(${target} PUBLIC cxx_std_20)
  lantern_warnings(${target})
endfunction()
