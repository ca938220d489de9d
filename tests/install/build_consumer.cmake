# Installs the build into a fresh PREFIX, then configures and builds the consumer program against
# it (CMAKE_PREFIX_PATH=PREFIX only, same generator, compiler and launcher; -Werror when WERROR).
# Run: cmake -DBUILD_DIR=... -DPREFIX=... -DCONSUMER_SOURCE=... -DCONSUMER_BUILD=... -DCXX=...
#        [-DGENERATOR=...] [-DBUILD_TYPE=...] [-DLAUNCHER=...] [-DWERROR=ON] -P build_consumer.cmake
foreach(var BUILD_DIR PREFIX CONSUMER_SOURCE CONSUMER_BUILD CXX)
  if(NOT ${var})
    message(FATAL_ERROR "build_consumer.cmake: -D${var}=... is required")
  endif()
endforeach()

file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX}
  OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
if(NOT EXISTS ${PREFIX}/lib/cmake/Lantern/LanternConfig.cmake)
  message(FATAL_ERROR "cmake --install wrote no ${PREFIX}/lib/cmake/Lantern/LanternConfig.cmake")
endif()

set(configure ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${CONSUMER_BUILD}
  -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_CXX_COMPILER=${CXX} -DCONSUMER_WERROR=${WERROR})
if(GENERATOR)
  list(APPEND configure -G ${GENERATOR})
endif()
if(BUILD_TYPE)
  list(APPEND configure -DCMAKE_BUILD_TYPE=${BUILD_TYPE})
endif()
if(LAUNCHER)
  list(APPEND configure -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
execute_process(COMMAND ${configure} COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${CONSUMER_BUILD} COMMAND_ERROR_IS_FATAL ANY)
message(STATUS "consumer built against ${PREFIX}")
