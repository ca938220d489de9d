// The à-trous step of denoise.atrous and denoise.atrous_modulate (the last step, which also
// brings the result back to radiance): see denoise_atrous.comp.
#ifndef LANTERN_DENOISE_ATROUS_GLSL
#define LANTERN_DENOISE_ATROUS_GLSL

#extension GL_EXT_control_flow_attributes : require

#include "denoise/denoise_common.glsl"

layout(binding = 0, rgba32f) readonly uniform image2D gbuffer_position;
layout(binding = 1) uniform utextureBuffer guide;
layout(binding = 2) uniform utextureBuffer accum_in;
layout(std430, binding = 4) readonly buffer LuminanceIn { float l[]; } luminance_in;

// The luminance the edge stop compares: denoise.variance's 3x3 means in iteration 0, else the
// input's own (already smoothed by the iterations before).
float stop_luminance(uint index, vec3 rgb) {
  return (push.flags & kDenoiseFlagSmoothLuminance) != 0u ? luminance_in.l[index] : luminance(rgb);
}

const float kKernel[2] = float[2](0.5, 0.25);

float filtered_variance(ivec2 pixel) {
  float sum = 0.0;
  float sum_w = 0.0;
  [[unroll]] for (int dy = -1; dy <= 1; ++dy) {
    [[unroll]] for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (!denoise_inside(q)) continue;
      float w = kKernel[abs(dx)] * kKernel[abs(dy)];
      sum += w * vec4_fetch(accum_in, denoise_index(q)).a;
      sum_w += w;
    }
  }
  return sum / sum_w;
}

// One à-trous step at pixel (index = denoise_index(pixel)): the filtered illumination and its
// variance; a pass-through pixel (sky, emitter) keeps its input.
vec4 atrous_step(ivec2 pixel, uint index) {
  vec4 centre = vec4_fetch(accum_in, index);
  vec4 g = vec4_fetch(guide, index);
  if (denoise_guide_sky(g)) return centre;
  vec3 n = denoise_guide_normal(g);
  float depth = denoise_view_depth(imageLoad(gbuffer_position, pixel).w);
  float l = stop_luminance(index, centre.rgb);
  float lum_scale = push.phi_luminance * sqrt(max(min(filtered_variance(pixel), centre.a), 0.0)) + 1e-6;
  int step = int(push.step);

  float w0 = kKernel[0] * kKernel[0];
  vec3 sum = w0 * centre.rgb;
  float sum_w = w0;
  float sum_var = w0 * w0 * centre.a;
  [[unroll]] for (int t = 0; t < 9; ++t) {
    if (t == 4) continue;  // the centre, weighted above
    ivec2 o = ivec2(t % 3 - 1, t / 3 - 1);
    ivec2 q = pixel + o * step;
    if (!denoise_inside(q)) continue;
    uint qi = denoise_index(q);
    vec4 gq = vec4_fetch(guide, qi);
    if (denoise_guide_sky(gq)) continue;
    vec4 c = vec4_fetch(accum_in, qi);
    float w = kKernel[abs(o.x)] * kKernel[abs(o.y)] *
              denoise_geometry_weight(g, n, depth, gq, float(step),
                                      abs(stop_luminance(qi, c.rgb) - l) / lum_scale);
    sum += w * c.rgb;
    sum_var += w * w * c.a;
    sum_w += w;
  }
  return vec4(sum / sum_w, sum_var / (sum_w * sum_w));
}

#endif
