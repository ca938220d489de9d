// gbuffer.draws: one VkDrawIndirectCommand per instance for the gbuffer raster pass, from the
// instance records on the GPU (the host never holds per-instance index counts): vertexCount =
// the instance's index count (non-indexed draw, vertex pulling), one instance, first vertex 0.
// Reads: scene_instances. Writes: gbuffer_draws (uvec4 per instance). History: none.
// Dispatch: ceil(instance_count / 64) workgroups of 64.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "gbuffer/gbuffer_push.h"
#include "shared/scene.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer InstanceBuffer { GpuInstance i[]; } scene_instances;
layout(std430, binding = 1) writeonly buffer DrawBuffer { uvec4 commands[]; } gbuffer_draws;

layout(push_constant) uniform Push { GBufferDrawsPush push; };

void main() {
  uint instance = gl_GlobalInvocationID.x;
  if (instance >= push.instance_count) return;
  // Whole triangles only: a trailing partial triangle would be dropped by the rasteriser anyway.
  uint index_count = scene_instances.i[instance].geometry.z / 3u * 3u;
  gbuffer_draws.commands[instance] = uvec4(index_count, 1u, 0u, 0u);
}
