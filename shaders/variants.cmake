# Extra shader variants: lantern_compile_shader(<source> <variant> DEFINES NAME=VALUE ...).
# The default variant of every stage is compiled by shaders/CMakeLists.txt.

# Visibility backends (shaders/lib/visibility.glsl, lighting/visibility/visibility_backend.h):
# every pass that includes lib/visibility.glsl gets a "rayquery" variant (and the probe a
# storage-buffer BVH one for the A/B benchmark). Add new passes to LANTERN_VISIBILITY_SHADERS.
set(LANTERN_VISIBILITY_SHADERS
  ${CMAKE_CURRENT_SOURCE_DIR}/integrators/baseline.comp
  ${CMAKE_CURRENT_SOURCE_DIR}/integrators/reference.comp
  ${CMAKE_CURRENT_SOURCE_DIR}/restir/restir_initial.comp
  ${CMAKE_CURRENT_SOURCE_DIR}/restir/restir_shade.comp
  ${CMAKE_CURRENT_SOURCE_DIR}/volume/volume_camera.comp
  ${CMAKE_CURRENT_SOURCE_DIR}/volume/volume_restir_initial.comp
  ${CMAKE_CURRENT_SOURCE_DIR}/volume/volume_restir_spatial.comp
  ${CMAKE_CURRENT_SOURCE_DIR}/tests/visibility_probe.comp)
foreach(src IN LISTS LANTERN_VISIBILITY_SHADERS)
  lantern_compile_shader(${src} rayquery DEFINES LANTERN_VISIBILITY_RAY_QUERY)
endforeach()
# Host visibility (shared/host_visibility.h): the passes whose one shadow ray per pixel the host
# traces run twice, writing rays ("hostemit") and shading with the answers ("hostresolve").
foreach(src IN ITEMS ${CMAKE_CURRENT_SOURCE_DIR}/integrators/baseline.comp
                     ${CMAKE_CURRENT_SOURCE_DIR}/restir/restir_shade.comp)
  lantern_compile_shader(${src} hostemit DEFINES LANTERN_VISIBILITY_HOST_EMIT)
  lantern_compile_shader(${src} hostresolve DEFINES LANTERN_VISIBILITY_HOST_RESOLVE)
endforeach()
# Host closest hits (shared/host_visibility.h's HostClosestRay): restir.initial's BSDF candidate
# rays written ("closestemit") and their hits read ("closestresolve").
lantern_compile_shader(${CMAKE_CURRENT_SOURCE_DIR}/restir/restir_initial.comp closestemit
  DEFINES LANTERN_VISIBILITY_HOST_CLOSEST_EMIT)
lantern_compile_shader(${CMAKE_CURRENT_SOURCE_DIR}/restir/restir_initial.comp closestresolve
  DEFINES LANTERN_VISIBILITY_HOST_CLOSEST_RESOLVE)
lantern_compile_shader(${CMAKE_CURRENT_SOURCE_DIR}/tests/visibility_probe.comp storage
  DEFINES VIS_BVH_STORAGE_BUFFERS)
# The host G-buffer method (lighting/gbuffer/gbuffer_pass.h): the resolve reads one
# (instance, triangle) record per pixel that Embree found on the host.
lantern_compile_shader(${CMAKE_CURRENT_SOURCE_DIR}/gbuffer/gbuffer_resolve.frag hosthits
  DEFINES LANTERN_GBUFFER_HOST_HITS)
