// The à-trous step of denoise.atrous and denoise.atrous_modulate (the last step, which also
// brings the result back to radiance): see denoise_atrous.comp.
#ifndef LANTERN_DENOISE_ATROUS_GLSL
#define LANTERN_DENOISE_ATROUS_GLSL

#extension GL_EXT_control_flow_attributes : require

#include "denoise/denoise_common.glsl"

layout(binding = 1) uniform utextureBuffer guide;
layout(binding = 2) uniform utextureBuffer accum_in;
layout(std430, binding = 4) readonly buffer LuminanceIn { float l[]; } luminance_in;

// The luminance the edge stop compares: denoise.variance's 3x3 means in iteration 0, else the
// input's own (already smoothed by the iterations before).
float stop_luminance(uint index, vec3 rgb) {
  return (push.flags & kDenoiseFlagSmoothLuminance) != 0u ? luminance_in.l[index] : luminance(rgb);
}

// The pixel pair of this invocation (shared/denoise.h): p0 and p0 + (step, 0), which share 6 of
// their 9 taps; false when p0 is outside, has_second false where p0 + step is.
bool atrous_pair(out ivec2 p0, out bool has_second) {
  uint column = gl_GlobalInvocationID.x;
  p0 = ivec2(int(denoise_atrous_pair_first(column, push.step)), int(gl_GlobalInvocationID.y));
  has_second = p0.x + int(push.step) < int(push.width);
  return column < denoise_atrous_pair_columns(push.width, push.step) && denoise_inside(p0);
}

// One à-trous step at both pixels of a pair (result[1] only when has_second): the filtered
// illumination and its variance; a pass-through pixel (denoise_passthrough, its guide
// denoise_guide_passthrough: `passthrough`) keeps its input. The
// 4x3 taps (columns p0.x - step .. p0.x + 2 step, rows p0.y - step .. p0.y + step) are read once
// for both: 12 reads for two pixels instead of 18 (night_market 320x180, with one exp per tap in
// denoise_geometry_weight: the denoiser 0.85-0.9x, 23.3-24.8% of the ReSTIR frame against
// 25.8-27.5%; images equal to the per-pixel step's to 4 digits of trade's relMSE).
void atrous_step_pair(ivec2 p0, bool has_second, out vec4 result[2], out bool passthrough[2]) {
  int step = int(push.step);
  vec4 tap_guide[12];
  vec4 tap_accum[12];
  float tap_luminance[12];
  bool tap_inside[12];
  [[unroll]] for (int t = 0; t < 12; ++t) {
    ivec2 q = p0 + ivec2(t % 4 - 1, t / 4 - 1) * step;
    tap_inside[t] = denoise_inside(q);
    tap_guide[t] = vec4(0.0);
    tap_accum[t] = vec4(0.0);
    tap_luminance[t] = 0.0;
    if (tap_inside[t]) {
      uint qi = denoise_index(q);
      tap_guide[t] = vec4_fetch(guide, qi);
      tap_accum[t] = vec4_fetch(accum_in, qi);
      tap_luminance[t] = stop_luminance(qi, tap_accum[t].rgb);
    }
  }
  [[unroll]] for (int k = 0; k < 2; ++k) {
    const int centre_tap = 5 + k;  // column k + 1 of the middle row
    vec4 centre = tap_accum[centre_tap];
    vec4 g = tap_guide[centre_tap];
    result[k] = centre;
    passthrough[k] = denoise_guide_sky(g);
    if ((k == 1 && !has_second) || passthrough[k]) continue;
    ivec2 pixel = p0 + ivec2(k * step, 0);
    vec3 n = denoise_guide_normal(g);
    float depth = denoise_guide_distance(g);
    float l = tap_luminance[centre_tap];
    const bool emitter = denoise_record_emitter(centre);
    const float centre_variance = denoise_record_variance(centre);
    // The centre's variance through a 3x3 Gaussian of its neighbours (SVGF): the taps themselves
    // in iteration 0 (spacing 1), its own reads otherwise. A pass-through neighbour carries no
    // variance (0), and one of the other kind counts as such (denoise_record_variance_as: an
    // emitter's heavy-tailed variance loosened the luminance stop of the dark surface beside it,
    // night_market's denoised relMSE +2-8%).
    float var_sum = 0.0;
    float var_w = 0.0;
    if (step == 1) {
      [[unroll]] for (int t = 0; t < 12; ++t) {
        int ox = t % 4 - 1 - k;
        int oy = t / 4 - 1;
        if (ox < -1 || ox > 1 || !tap_inside[t]) continue;
        float w = kDenoiseKernel[abs(ox)] * kDenoiseKernel[abs(oy)];
        var_sum += w * denoise_record_variance_as(tap_accum[t], emitter);
        var_w += w;
      }
    } else {
      [[unroll]] for (int t = 0; t < 9; ++t) {
        ivec2 o = ivec2(t % 3 - 1, t / 3 - 1);
        ivec2 q = pixel + o;
        if (!denoise_inside(q)) continue;
        float w = kDenoiseKernel[abs(o.x)] * kDenoiseKernel[abs(o.y)];
        var_sum += w * (t == 4 ? centre_variance
                               : denoise_record_variance_as(vec4_fetch(accum_in, denoise_index(q)),
                                                            emitter));
        var_w += w;
      }
    }
    float lum_scale =
        push.phi_luminance * sqrt(max(min(var_sum / var_w, centre_variance), 0.0)) + 1e-6;
    float w0 = kDenoiseKernel[0] * kDenoiseKernel[0];
    vec3 sum = w0 * centre.rgb;
    float sum_w = w0;
    float sum_var = w0 * w0 * centre_variance;
    [[unroll]] for (int t = 0; t < 12; ++t) {
      int ox = t % 4 - 1 - k;
      int oy = t / 4 - 1;
      if (ox < -1 || ox > 1 || t == centre_tap || !tap_inside[t]) continue;
      vec4 gq = tap_guide[t];
      vec4 c = tap_accum[t];
      if (denoise_guide_sky(gq) || denoise_record_emitter(c) != emitter) continue;
      float w = kDenoiseKernel[abs(ox)] * kDenoiseKernel[abs(oy)] *
                denoise_geometry_weight(g, n, depth, gq, float(step),
                                        abs(tap_luminance[t] - l) / lum_scale);
      sum += w * c.rgb;
      sum_var += w * w * denoise_record_variance(c);
      sum_w += w;
    }
    result[k] = denoise_record(sum / sum_w, sum_var / (sum_w * sum_w), emitter);
  }
}

#endif
