# Fails when a layer includes a layer above it or a library it must not use
# (engine: no Vulkan, no GLFW, no OpenVDB, no runtime/lighting; runtime: no lighting; lighting: no
# GLFW, no OpenVDB: volume I/O is the runtime's).
# Run: cmake -DSOURCE_DIR=<repo> -P check_layers.cmake
set(rules
  "engine|vulkan/|GLFW/|runtime/|lighting/|apps/|openvdb/"
  "runtime|lighting/|apps/"
  "lighting|GLFW/|apps/|runtime/window/|openvdb/"
  "shaders/shared|engine/|runtime/|lighting/|vulkan/")
set(violations "")
foreach(rule IN LISTS rules)
  string(REPLACE "|" ";" parts "${rule}")
  list(POP_FRONT parts layer)
  file(GLOB_RECURSE files ${SOURCE_DIR}/${layer}/*.h ${SOURCE_DIR}/${layer}/*.cpp ${SOURCE_DIR}/${layer}/*.hpp)
  foreach(f IN LISTS files)
    file(STRINGS ${f} includes REGEX "^[ \t]*#[ \t]*include")
    foreach(line IN LISTS includes)
      foreach(forbidden IN LISTS parts)
        string(FIND "${line}" "${forbidden}" at)
        if(NOT at EQUAL -1)
          file(RELATIVE_PATH rel ${SOURCE_DIR} ${f})
          string(APPEND violations "  ${rel}: ${line}  (${layer} may not include ${forbidden})\n")
        endif()
      endforeach()
    endforeach()
  endforeach()
  list(LENGTH files count)
  if(count EQUAL 0)
    message(FATAL_ERROR "layer ${layer}: no sources found under ${SOURCE_DIR}/${layer}")
  endif()
endforeach()
if(violations)
  message(FATAL_ERROR "layering violations:\n${violations}")
endif()
message(STATUS "layers clean")
