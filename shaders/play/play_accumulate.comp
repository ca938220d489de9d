// play.accumulate: progressive accumulation while nothing moves (`lantern play` with the
// reference or baseline integrator): sum = (count == 1 ? 0 : sum) + hdr, then hdr = sum / count.
// Non-finite input counts as 0. Reads/writes: hdr, play.accum (history buffer). Dispatch: one
// thread per pixel, 64 per group.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "play/play_ui.h"
#include "shared/common_math.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer HdrBuffer { vec4 pixels[]; } hdr;
layout(std430, binding = 1) buffer AccumBuffer { vec4 pixels[]; } accum;
layout(push_constant) uniform Push { PlayAccumulatePush push; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.pixels) return;
  vec4 c = hdr.pixels[i];
  vec3 v = vec3(finite_positive_or_zero(c.r), finite_positive_or_zero(c.g),
                finite_positive_or_zero(c.b));
  vec3 sum = (push.count <= 1u ? vec3(0.0) : accum.pixels[i].rgb) + v;
  accum.pixels[i] = vec4(sum, 1.0);
  hdr.pixels[i] = vec4(sum / float(max(push.count, 1u)), 1.0);
}
