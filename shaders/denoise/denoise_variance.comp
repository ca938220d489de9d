// denoise.variance: where the temporal history is short (< kDenoiseShortHistory frames: just
// disoccluded, the first frame, after a cut) the temporal variance means little yet; estimate it
// from the luminance of similar neighbours in a 5x5 window instead (depth-plane and normal edge
// stops as in denoise.atrous, neighbours of the pixel's kind only: denoise_record), so the first
// à-trous iterations still know how noisy the pixel is. From kDenoiseOwnSpreadHistory frames on
// the pixel's own samples' spread bounds that estimate, never below kDenoiseOwnSpreadFloor of the
// smaller of it and the similar neighbours' own spread.
// Also the 3x3 mean luminance of similar neighbours (tent-weighted, kDenoiseKernel), which the
// first à-trous iteration's luminance edge stop compares.
// Reads: accum_in (rgb illumination, a variance), moments_in (z history length), guide.
// Writes: accum_out (same layout), luminance_out.
// History: none.
// Dispatch: one thread per pixel, lib/pixel_groups.glsl groups.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "denoise/denoise_common.glsl"

layout(binding = 1) uniform utextureBuffer guide;
layout(binding = 2) uniform utextureBuffer accum_in;
layout(binding = 3) uniform utextureBuffer moments_in;
layout(std430, binding = 4) writeonly buffer AccumOut { vec4 p[]; } accum_out;
layout(std430, binding = 5) writeonly buffer LuminanceOut { float l[]; } luminance_out;

void main() {
  ivec2 pixel;
  if (!denoise_pixel(pixel)) return;
  uint index = denoise_index(pixel);
  vec4 centre = vec4_fetch(accum_in, index);
  vec4 g = vec4_fetch(guide, index);
  float frames = vec4_fetch(moments_in, index).z;
  if (denoise_guide_sky(g)) {
    accum_out.p[index] = centre;
    luminance_out.l[index] = 0.0;
    return;
  }
  vec3 n = denoise_guide_normal(g);
  const bool emitter = denoise_record_emitter(centre);
  float depth = denoise_guide_distance(g);
  // The first à-trous iteration's luminance edge stop compares these 3x3 means, not single
  // samples: a bright sample among dark neighbours (ReSTIR's heavy tail) is not rejected by all
  // of them while it spreads itself over them (which lost 5% of night_market's energy). The tent
  // keeps the centre in front: with equal weights two pixels of a strip two pixels wide, one lit
  // and one in shadow, had the same mean, and the stop let the lit one into the dark one
  // (cornell_lights: a steady 0.2-0.3 on pixels that are black; trade's denoised relMSE 6-16%
  // lower with the tent).
  // The 3x3 taps also start the short-history moments below (geometry weights only), so the
  // 5x5 window reads just its outer ring of 16 on top; with them the mean of the neighbours' own
  // spread (their temporal variance), which floors the own-spread bound.
  float smooth_sum = 0.0;
  float smooth_w = 0.0;
  float sum_w = 0.0;
  vec2 moments = vec2(0.0);
  float neighbours_spread = 0.0;
  [[unroll]] for (int t = 0; t < 9; ++t) {
    ivec2 q = pixel + ivec2(t % 3 - 1, t / 3 - 1);
    if (!denoise_inside(q)) continue;
    uint qi = denoise_index(q);
    vec4 gq = vec4_fetch(guide, qi);
    vec4 rq = vec4_fetch(accum_in, qi);
    if (denoise_guide_sky(gq) || denoise_record_emitter(rq) != emitter) continue;
    float wg = denoise_geometry_weight(g, n, depth, gq, 1.0, 0.0);
    float w = kDenoiseKernel[abs(t % 3 - 1)] * kDenoiseKernel[abs(t / 3 - 1)] * wg;
    float l = luminance(rq.rgb);
    smooth_sum += w * l;
    smooth_w += w;
    moments += wg * vec2(l, l * l);
    neighbours_spread += wg * denoise_record_variance(rq);
    sum_w += wg;
  }
  luminance_out.l[index] = smooth_sum / max(smooth_w, 1e-6);
  if (frames >= kDenoiseShortHistory) {
    accum_out.p[index] = centre;
    return;
  }
  [[unroll]] for (int dy = -2; dy <= 2; ++dy) {
    [[unroll]] for (int dx = -2; dx <= 2; ++dx) {
      if (abs(dx) < 2 && abs(dy) < 2) continue;  // the 3x3 above
      ivec2 q = pixel + ivec2(dx, dy);
      if (!denoise_inside(q)) continue;
      uint qi = denoise_index(q);
      vec4 gq = vec4_fetch(guide, qi);
      vec4 rq = vec4_fetch(accum_in, qi);
      if (denoise_guide_sky(gq) || denoise_record_emitter(rq) != emitter) continue;
      float w = denoise_geometry_weight(g, n, depth, gq, 1.0, 0.0);
      float l = luminance(rq.rgb);
      moments += w * vec2(l, l * l);
      neighbours_spread += w * denoise_record_variance(rq);
      sum_w += w;
    }
  }
  moments /= max(sum_w, 1e-6);
  neighbours_spread /= max(sum_w, 1e-6);
  // The spatial estimate as it is: its moments come from up to 25 pixels. SVGF boosts it by
  // kDenoiseShortHistory / frames; that widened the first à-trous steps' luminance stop for a
  // pixel just disoccluded to twice its neighbours' spread, and a pixel in a contact shadow took
  // the lit surface's light around it (night_market: denoised relMSE -4 to -11% on seeds 1-6,
  // the means unchanged, README "Two neighbours vouch for a sample"). The pixel's own spread,
  // from 2 or 3 frames, is boosted: fewer frames behind it, more uncertain.
  float boost = kDenoiseShortHistory / max(frames, 1.0);
  float variance = max(moments.y - moments.x * moments.x, 0.0);
  if (frames >= kDenoiseOwnSpreadHistory) {
    float floor_variance = kDenoiseOwnSpreadFloor * min(variance, neighbours_spread * boost);
    variance = max(min(variance, denoise_record_variance(centre) * boost), floor_variance);
  }
  accum_out.p[index] = denoise_record(centre.rgb, variance, emitter);
}
