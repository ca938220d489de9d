// upscale.temporal: reconstructs the output-size image from this frame's internal-size HDR image
// and last frame's output: the current samples resampled bilinearly at the output pixel centre
// (minus the sample jitter), last frame's output reprojected along the scene's own motion
// (gbuffer.motion's zw: without the jitter step, since the output history is not jittered; a
// still view keeps every output pixel's history where it is), scaled to output pixels,
// fetched by Catmull-Rom over 4x4 output pixels, and rectified (clamped to the min/max of the 3x3
// current samples around the pixel: stale history, e.g. a moving emitter's trail, cannot
// survive), then blended (push.history_weight). At scale 1 with no jitter the weight is 0: the
// input comes out as it is.
// Reads: hdr_in and gbuffer_motion (internal size), history (output size).
// Writes: hdr_out ("upscale.color", output size). History: "upscale.color" of last frame;
// without kUpscaleFlagHistoryValid the history binding is a stand-in and is not read.
// Dispatch: one thread per output pixel, lib/pixel_groups.glsl groups.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "shared/common_math.h"
#include "shared/upscale.h"

#include "lib/pixel_groups.glsl"
#include "lib/texel_records.glsl"

layout(push_constant) uniform Push { UpscalePush push; };

layout(binding = 0, rgba32f) readonly uniform image2D gbuffer_motion;
layout(binding = 1) uniform utextureBuffer hdr_in;
layout(binding = 2) uniform utextureBuffer history;
layout(std430, binding = 3) writeonly buffer HdrOut { vec4 p[]; } hdr_out;

vec3 finite3(vec3 c) {
  return vec3(finite_positive_or_zero(c.r), finite_positive_or_zero(c.g),
              finite_positive_or_zero(c.b));
}

vec3 load_in(ivec2 q) {
  q = clamp(q, ivec2(0), ivec2(push.in_width, push.in_height) - 1);
  return finite3(vec4_fetch(hdr_in, uint(q.y) * push.in_width + uint(q.x)).rgb);
}

vec3 load_history(ivec2 q) {
  q = clamp(q, ivec2(0), ivec2(push.out_width, push.out_height) - 1);
  return vec4_fetch(history, uint(q.y) * push.out_width + uint(q.x)).rgb;
}

// Catmull-Rom weights of the four texels around a sample t (0..1) past the second: a cubic that
// passes through the texels, so a still view (t = 0: weights 0, 1, 0, 0) fetches the history
// exactly, and a moving one is not blurred a little more with every frame it is reprojected, as
// a bilinear tap blurs it (night_market at half size: the upscaled image kept 0.85 -> 0.87 of the
// energy, README "Upscaling measured against the full-size reference").
vec4 catmull_rom_weights(float t) {
  float t2 = t * t;
  float t3 = t2 * t;
  return vec4(-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t,
              0.5 * t3 - 0.5 * t2);
}

// The history at u (texel coordinates: texel q's centre at q), Catmull-Rom over the 4x4 texels
// around it; its negative lobes can overshoot, which the clamp to this frame's neighbourhood
// (and 0 here) takes back.
vec3 bicubic_history(vec2 u) {
  ivec2 b = ivec2(floor(u));
  vec2 f = u - vec2(b);
  vec4 wx = catmull_rom_weights(f.x);
  vec4 wy = catmull_rom_weights(f.y);
  vec3 sum = vec3(0.0);
  [[unroll]] for (int j = 0; j < 4; ++j) {
    vec3 row = vec3(0.0);
    [[unroll]] for (int i = 0; i < 4; ++i) row += wx[i] * load_history(b + ivec2(i - 1, j - 1));
    sum += wy[j] * row;
  }
  return max(sum, vec3(0.0));
}

// Bilinear weights along one axis over the three texels n - 1, n, n + 1 for a sample at b + f,
// where b = floor(u) is n - 1 or n (n = the texel nearest u).
vec3 bilinear_weights(int b, int n, float f) {
  return b < n ? vec3(1.0 - f, f, 0.0) : vec3(0.0, 1.0 - f, f);
}

void main() {
  ivec2 o = ivec2(gl_GlobalInvocationID.xy);
  if (o.x >= int(push.out_width) || o.y >= int(push.out_height)) return;
  vec2 in_size = vec2(push.in_width, push.in_height);
  vec2 out_size = vec2(push.out_width, push.out_height);
  vec2 u = (vec2(o) + 0.5) * (in_size / out_size) - 0.5 - push.jitter;
  // The 3x3 internal texels around the nearest one hold the bilinear footprint and the
  // neighbourhood that rectifies the history: each is read once.
  ivec2 b = ivec2(floor(u));
  vec2 f = u - vec2(b);
  ivec2 n = clamp(ivec2(floor(u + 0.5)), ivec2(0), ivec2(in_size) - 1);
  vec3 wx = bilinear_weights(b.x, n.x, f.x);
  vec3 wy = bilinear_weights(b.y, n.y, f.y);
  vec3 current = vec3(0.0);
  vec3 lo = vec3(3.0e38);
  vec3 hi = vec3(0.0);
  [[unroll]] for (int t = 0; t < 9; ++t) {
    vec3 c = load_in(n + ivec2(t % 3 - 1, t / 3 - 1));
    current += (wx[t % 3] * wy[t / 3]) * c;
    lo = min(lo, c);
    hi = max(hi, c);
  }
  vec3 result = current;
  if ((push.flags & kUpscaleFlagHistoryValid) != 0u && push.history_weight > 0.0) {
    // The point's own motion (zw; xy leads to last frame's jittered sample instead).
    vec2 motion = imageLoad(gbuffer_motion, n).zw * (out_size / in_size);
    vec2 previous = vec2(o) + 0.5 + motion;
    if (is_finite(motion.x) && is_finite(motion.y) && all(greaterThanEqual(previous, vec2(0.0))) &&
        all(lessThan(previous, out_size))) {
      vec3 h = clamp(bicubic_history(previous - 0.5), lo, hi);
      result = mix(current, h, push.history_weight);
    }
  }
  hdr_out.p[uint(o.y) * push.out_width + uint(o.x)] = vec4(result, 1.0);
}
