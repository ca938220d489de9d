// Build-time check that shaders/lib/bvh_traverse.glsl compiles (storage-buffer variant), and a
// ready ray-casting kernel for GPU-vs-CPU tests: one closest-hit and one any-hit query per ray.
// The texel-buffer variant is compiled by bvh_compile_probe_texel.comp.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lib/bvh_traverse.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 1, binding = 0) readonly buffer Rays {
  BvhRay rays[];
};
layout(std430, set = 1, binding = 1) writeonly buffer Hits {
  BvhHit hits[];
};
layout(std430, set = 1, binding = 2) writeonly buffer Occluded {
  uint occluded[];
};
layout(push_constant) uniform Push {
  uint ray_count;
};

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= ray_count) return;
  BvhHit hit;
  if (!bvh_trace_closest(rays[i], hit)) hit.instance = 0xffffffffu;
  hits[i] = hit;
  occluded[i] = bvh_trace_any(rays[i]) ? 1u : 0u;
}
