// denoise.variance: where the temporal history is short (< kDenoiseShortHistory frames: just
// disoccluded, the first frame, after a cut) the temporal variance means nothing yet; estimate it
// from the luminance of similar neighbours in a 7x7 window instead (depth-plane and normal edge
// stops as in denoise.atrous), so the first à-trous iterations still know how noisy the pixel is.
// Reads: accum_in (rgb illumination, a variance), moments_in (z history length), guide,
// gbuffer position (the centre's view depth). Writes: accum_out (same layout). History: none.
// Dispatch: one thread per pixel, 8x8 groups.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "denoise/denoise_common.glsl"

layout(binding = 0, rgba32f) readonly uniform image2D gbuffer_position;
layout(std430, binding = 1) readonly buffer Guide { vec4 p[]; } guide;
layout(std430, binding = 2) readonly buffer AccumIn { vec4 p[]; } accum_in;
layout(std430, binding = 3) readonly buffer MomentsIn { vec4 p[]; } moments_in;
layout(std430, binding = 4) writeonly buffer AccumOut { vec4 p[]; } accum_out;

void main() {
  ivec2 pixel;
  if (!denoise_pixel(pixel)) return;
  uint index = denoise_index(pixel);
  vec4 centre = accum_in.p[index];
  vec4 g = guide.p[index];
  float frames = moments_in.p[index].z;
  if (denoise_guide_sky(g) || frames >= kDenoiseShortHistory) {
    accum_out.p[index] = centre;
    return;
  }
  vec3 n = denoise_guide_normal(g);
  float depth = imageLoad(gbuffer_position, pixel).w;
  float sum_w = 0.0;
  vec2 moments = vec2(0.0);
  [[unroll]] for (int dy = -3; dy <= 3; ++dy) {
    [[unroll]] for (int dx = -3; dx <= 3; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (!denoise_inside(q)) continue;
      uint qi = denoise_index(q);
      vec4 gq = guide.p[qi];
      if (denoise_guide_sky(gq)) continue;
      float w = denoise_geometry_weight(g, n, depth, gq, 1.0, 0.0);
      float l = luminance(accum_in.p[qi].rgb);
      moments += w * vec2(l, l * l);
      sum_w += w;
    }
  }
  moments /= max(sum_w, 1e-6);
  // Fewer frames behind it: more uncertain (SVGF's boost of the spatial estimate).
  float boost = kDenoiseShortHistory / max(frames, 1.0);
  accum_out.p[index] = vec4(centre.rgb, max(moments.y - moments.x * moments.x, 0.0) * boost);
}
