// gbuffer.draws: sets up the culled visibility raster from the instance records on the GPU (the
// host never holds per-instance index counts): each instance's first cull chunk (exclusive
// prefix sum of ceil(triangles / kGBufferCullChunk)), the indirect dispatch of gbuffer.cull (one
// workgroup per chunk) and the indirect draw of gbuffer with vertexCount 0 (gbuffer.cull adds 3
// per surviving triangle). For the forward method: one VkDrawIndirectCommand per instance.
// Reads: scene_instances. Writes: gbuffer_chunks, gbuffer_dispatch, gbuffer_draw (culled), or
// gbuffer_draws (forward). History: none. Dispatch: one workgroup of 256 threads (each sums a
// contiguous run of instances; a shared-memory scan joins the runs).
#version 460
#extension GL_GOOGLE_include_directive : require

#include "gbuffer/gbuffer_push.h"
#include "lib/scene_buffers.glsl"

layout(local_size_x = 256) in;
layout(constant_id = 0) const bool kForward = false;

layout(std430, binding = PASS_BINDING(0)) writeonly buffer ChunkBuffer {
  uint first[];
} gbuffer_chunks;
layout(std430, binding = PASS_BINDING(1)) writeonly buffer DispatchBuffer {
  uint words[];
} gbuffer_dispatch;
layout(std430, binding = PASS_BINDING(2)) writeonly buffer DrawBuffer {
  uvec4 commands[];
} gbuffer_draw;

layout(push_constant) uniform Push { GBufferDrawsPush push; };

shared uint run_sums[256];

// Whole triangles only: a trailing partial triangle would be dropped by the rasteriser anyway.
uint triangles_of(uint instance) { return scene_instances.i[instance].geometry.z / 3u; }

void main() {
  uint n = push.instance_count;
  uint t = gl_LocalInvocationID.x;
  if (kForward) {
    for (uint instance = t; instance < n; instance += 256u) {
      gbuffer_draw.commands[instance] = uvec4(3u * triangles_of(instance), 1u, 0u, 0u);
    }
    return;
  }
  uint per_thread = (n + 255u) / 256u;
  uint begin = min(t * per_thread, n);
  uint end = min(begin + per_thread, n);
  uint sum = 0u;
  for (uint instance = begin; instance < end; ++instance) {
    sum += (triangles_of(instance) + kGBufferCullChunk - 1u) / kGBufferCullChunk;
  }
  run_sums[t] = sum;
  barrier();
  // Inclusive Hillis-Steele scan over the 256 run sums.
  for (uint offset = 1u; offset < 256u; offset *= 2u) {
    uint add = t >= offset ? run_sums[t - offset] : 0u;
    barrier();
    run_sums[t] += add;
    barrier();
  }
  uint first = run_sums[t] - sum;
  for (uint instance = begin; instance < end; ++instance) {
    gbuffer_chunks.first[instance] = first;
    first += (triangles_of(instance) + kGBufferCullChunk - 1u) / kGBufferCullChunk;
  }
  if (t == 0u) {
    gbuffer_dispatch.words[0] = run_sums[255];
    gbuffer_dispatch.words[1] = 1u;
    gbuffer_dispatch.words[2] = 1u;
    gbuffer_draw.commands[0] = uvec4(0u, 1u, 0u, 0u);
  }
}
