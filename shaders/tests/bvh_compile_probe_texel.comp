// Build-time check of the texel-buffer variant of shaders/lib/bvh_traverse.glsl (rgba32ui
// usamplerBuffer fetches, the layout PLATFORM.md measured fastest on lavapipe).
#version 460
#extension GL_GOOGLE_include_directive : require

#define BVH_TEXEL_BUFFERS
#include "lib/bvh_traverse.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 1, binding = 0) readonly buffer Rays {
  BvhRay rays[];
};
layout(std430, set = 1, binding = 1) writeonly buffer Occluded {
  uint occluded[];
};
layout(push_constant) uniform Push {
  uint ray_count;
};

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= ray_count) return;
  vec3 origin = rays[i].origin.xyz;
  vec3 target = origin + rays[i].direction.xyz;
  occluded[i] = bvh_visible(origin, target) ? 0u : 1u;
}
