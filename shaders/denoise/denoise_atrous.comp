// denoise.atrous (iteration i of N): one edge-avoiding à-trous wavelet step (Dammertz et al.;
// SVGF, Schied et al. 2017): a 5x5 B3-spline kernel with taps 2^i pixels apart, each tap weighted
// by the depth plane (world distance from the centre's tangent plane relative to its view depth),
// the normals, and the luminance difference in units of the centre's filtered standard deviation
// (3x3 Gaussian of the variance). Weights are normalised (a constant image stays constant);
// variance propagates as sum w^2 var / (sum w)^2. Sky pixels pass through.
// Reads: accum_in (rgb illumination, a variance), gbuffer position/normal.
// Writes: accum_out (iteration 0 writes "denoise.color", next frame's temporal history).
// History: none. Dispatch: one thread per pixel, 8x8 groups.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "denoise/denoise_common.glsl"

layout(binding = 0, rgba32f) readonly uniform image2D gbuffer_position;
layout(binding = 1, rgba32f) readonly uniform image2D gbuffer_normal;
layout(std430, binding = 2) readonly buffer AccumIn { vec4 p[]; } accum_in;
layout(std430, binding = 3) writeonly buffer AccumOut { vec4 p[]; } accum_out;

const float kKernel[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);

float filtered_variance(ivec2 pixel) {
  float sum = 0.0;
  float sum_w = 0.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (!denoise_inside(q)) continue;
      float w = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
      sum += w * accum_in.p[denoise_index(q)].a;
      sum_w += w;
    }
  }
  return sum / sum_w;
}

void main() {
  ivec2 pixel;
  if (!denoise_pixel(pixel)) return;
  uint index = denoise_index(pixel);
  vec4 centre = accum_in.p[index];
  vec4 position = imageLoad(gbuffer_position, pixel);
  if (gbuffer_is_sky(position.w)) {
    accum_out.p[index] = centre;
    return;
  }
  vec3 n = oct_decode(imageLoad(gbuffer_normal, pixel).xy);
  float l = luminance(centre.rgb);
  float sigma = sqrt(max(filtered_variance(pixel), 0.0));
  float lum_scale = push.phi_luminance * sigma + 1e-6;
  int step = int(push.step);

  vec3 sum = vec3(0.0);
  float sum_w = 0.0;
  float sum_var = 0.0;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy) * step;
      if (!denoise_inside(q)) continue;
      vec4 qp = imageLoad(gbuffer_position, q);
      if (gbuffer_is_sky(qp.w)) continue;
      vec4 c = accum_in.p[denoise_index(q)];
      float w = kKernel[abs(dx)] * kKernel[abs(dy)];
      if (dx != 0 || dy != 0) {
        vec3 nq = oct_decode(imageLoad(gbuffer_normal, q).xy);
        float plane = abs(dot(n, qp.xyz - position.xyz));
        w *= exp(-plane / (push.phi_depth * position.w * float(step) + 1e-6) -
                 abs(luminance(c.rgb) - l) / lum_scale) *
             pow(max(dot(n, nq), 0.0), push.phi_normal);
      }
      sum += w * c.rgb;
      sum_var += w * w * c.a;
      sum_w += w;
    }
  }
  accum_out.p[index] = vec4(sum / sum_w, sum_var / (sum_w * sum_w));
}
