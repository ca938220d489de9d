// denoise.atrous (iteration i of the first N - 1; the last is denoise.atrous_modulate, the same
// step written back as radiance): one edge-avoiding à-trous wavelet step (Dammertz et al. 2010;
// SVGF, Schied et al. 2017) with a 3x3 B-spline kernel (1/4, 1/2, 1/4 per axis) whose taps are
// 2^i pixels apart, each tap weighted by the depth plane (distance from the centre's tangent plane
// relative to its distance from the camera), the normals, and the luminance difference in units of
// the centre's filtered standard deviation (3x3 Gaussian of the variance). Weights are normalised
// (a constant image stays constant); variance propagates as sum w^2 var / (sum w)^2. Sky pixels
// pass through.
// (3x3 rather than SVGF's 5x5: 9 taps instead of 25, the same reach with one more iteration.)
// Reads: accum_in (rgb illumination, a variance), guide, luminance_in (denoise.variance's 3x3
// means, iteration 0).
// Writes: accum_out.
// History: none. Dispatch: one thread per pixel pair (atrous_pair), lib/pixel_groups.glsl groups.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "denoise/denoise_atrous.glsl"

layout(std430, binding = 3) writeonly buffer AccumOut { vec4 p[]; } accum_out;

void main() {
  ivec2 p0;
  bool has_second;
  if (!atrous_pair(p0, has_second)) return;
  vec4 result[2];
  bool passthrough[2];
  atrous_step_pair(p0, has_second, result, passthrough);
  accum_out.p[denoise_index(p0)] = result[0];
  if (has_second) accum_out.p[denoise_index(p0 + ivec2(push.step, 0))] = result[1];
}
