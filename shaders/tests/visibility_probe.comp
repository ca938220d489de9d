// Visibility test and benchmark kernel (tests/visibility/): one ray per invocation through the
// shaders/lib/visibility.glsl interface, in whichever backend variant it was compiled as.
// mode 0: closest hit (vis_trace_closest, tmax = direction.w); mode 1: shadow ray towards
// origin + direction (vis_visible). Reads: rays. Writes: results (x = instance or ~0u on a miss,
// y = primitive, z = bits of t, w = 1 when visible (mode 1)). Dispatch: 1D, 64 rays per
// workgroup, workgroups shuffled (workgroup g handles block g * stride mod count, stride coprime
// with count) so that lavapipe's two contiguous halves of the grid get mixed work.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lib/visibility.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 4) readonly buffer RayBuffer { BvhRay r[]; } probe_rays;
layout(std430, set = 0, binding = 5) writeonly buffer ResultBuffer { uvec4 r[]; } probe_results;

layout(push_constant) uniform Push {
  uint ray_count;
  uint mode;
  uint group_count;
  uint group_stride;
} push;

void main() {
  uint group = (gl_WorkGroupID.x * push.group_stride) % push.group_count;
  uint i = group * 64u + gl_LocalInvocationID.x;
  if (i >= push.ray_count) return;
  BvhRay ray = probe_rays.r[i];
  uvec4 result = uvec4(~0u, 0u, 0u, 0u);
  if (push.mode == 0u) {
    VisHit hit;
    if (vis_trace_closest(ray.origin.xyz, ray.direction.xyz, ray.direction.w, hit))
      result = uvec4(hit.instance, hit.primitive, floatBitsToUint(hit.t), 0u);
  } else {
    result.w = vis_visible(ray.origin.xyz, ray.origin.xyz + ray.direction.xyz) ? 1u : 0u;
  }
  probe_results.r[i] = result;
}
