// The scene as every pass reads it: declares each scene buffer once, at the binding its slot
// names (shared/scene_bindings.h), under the name SceneHandles::bind binds it by
// (lighting/scene/scene_buffers.h):
//   frame_constants.frame (FrameConstants), scene_vertices.v[], scene_indices.i[],
//   scene_materials.m[], scene_instances.i[], scene_lights.l[], light_alias.e[],
//   light_previous_to_current.index[] (uint per last frame's light: its current index or
//   kInvalidLight), the BVH (lib/bvh_traverse.glsl: bvh_header, bvh_*_texels; in the rayquery
//   variant instead the TLAS scene_tlas at kSceneTlas) and the
//   environment (lib/environment.glsl: env_header, env_texels, env_marginal, env_conditional).
// Then lib/visibility.glsl's vis_trace_closest / vis_visible and frame_rng are available. A pass
// declares its own resources from kPassBindingBase on: layout(binding = PASS_BINDING(0)).
#ifndef LANTERN_LIB_SCENE_BUFFERS_GLSL
#define LANTERN_LIB_SCENE_BUFFERS_GLSL

#extension GL_GOOGLE_include_directive : require

#include "shared/alias_table.h"
#include "shared/lights.h"
#include "shared/rng.h"
#include "shared/scene.h"
#include "shared/scene_bindings.h"

#define PASS_BINDING(i) (kPassBindingBase + (i))

layout(std430, binding = kSceneFrameConstants) restrict readonly buffer FrameBuffer {
  FrameConstants frame;
} frame_constants;
layout(std430, binding = kSceneVertices) restrict readonly buffer VertexBuffer {
  GpuVertex v[];
} scene_vertices;
layout(std430, binding = kSceneIndices) restrict readonly buffer IndexBuffer {
  uint i[];
} scene_indices;
layout(std430, binding = kSceneMaterials) restrict readonly buffer MaterialBuffer {
  GpuMaterial m[];
} scene_materials;
layout(std430, binding = kSceneInstances) restrict readonly buffer InstanceBuffer {
  GpuInstance i[];
} scene_instances;
layout(std430, binding = kSceneLights) restrict readonly buffer LightBuffer {
  GpuLight l[];
} scene_lights;
layout(std430, binding = kSceneLightAlias) restrict readonly buffer AliasBuffer {
  AliasEntry e[];
} light_alias;
layout(std430, binding = kSceneLightPreviousToCurrent) restrict readonly buffer RemapBuffer {
  uint index[];
} light_previous_to_current;

#define VIS_BINDING_BASE kSceneBvhHeader
#define VIS_TLAS_BINDING kSceneTlas
#include "lib/visibility.glsl"
#define ENV_BINDING_BASE kSceneEnvHeader
#include "lib/environment.glsl"

// The random stream of `pixel` in pass `pass` this frame (the frame's index and seed are the
// frame constants').
uint frame_rng(uvec2 pixel, uint pass) {
  return rng_init(pixel, frame_constants.frame.frame.z, frame_constants.frame.frame.w, pass);
}

#endif
