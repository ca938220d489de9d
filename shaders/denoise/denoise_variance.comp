// denoise.variance: where the temporal history is short (< kDenoiseShortHistory frames: just
// disoccluded, the first frame, after a cut) the temporal variance means nothing yet; estimate it
// from the luminance of similar neighbours in a 7x7 window instead (depth-plane and normal edge
// stops as in denoise.atrous), so the first à-trous iterations still know how noisy the pixel is.
// Reads: accum_in (rgb illumination, a variance), moments_in (z history length), gbuffer
// position/normal. Writes: accum_out (same layout). History: none.
// Dispatch: one thread per pixel, 8x8 groups.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "denoise/denoise_common.glsl"

layout(binding = 0, rgba32f) readonly uniform image2D gbuffer_position;
layout(binding = 1, rgba32f) readonly uniform image2D gbuffer_normal;
layout(std430, binding = 2) readonly buffer AccumIn { vec4 p[]; } accum_in;
layout(std430, binding = 3) readonly buffer MomentsIn { vec4 p[]; } moments_in;
layout(std430, binding = 4) writeonly buffer AccumOut { vec4 p[]; } accum_out;

void main() {
  ivec2 pixel;
  if (!denoise_pixel(pixel)) return;
  uint index = denoise_index(pixel);
  vec4 centre = accum_in.p[index];
  vec4 position = imageLoad(gbuffer_position, pixel);
  if (gbuffer_is_sky(position.w) || moments_in.p[index].z >= kDenoiseShortHistory) {
    accum_out.p[index] = centre;
    return;
  }
  vec3 n = oct_decode(imageLoad(gbuffer_normal, pixel).xy);
  float sum_w = 0.0;
  vec2 moments = vec2(0.0);
  for (int dy = -3; dy <= 3; ++dy) {
    for (int dx = -3; dx <= 3; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (!denoise_inside(q)) continue;
      vec4 qp = imageLoad(gbuffer_position, q);
      if (gbuffer_is_sky(qp.w)) continue;
      vec3 nq = oct_decode(imageLoad(gbuffer_normal, q).xy);
      float plane = abs(dot(n, qp.xyz - position.xyz));
      float w = exp(-plane / (push.phi_depth * position.w + 1e-6)) *
                pow(max(dot(n, nq), 0.0), push.phi_normal);
      float l = luminance(accum_in.p[denoise_index(q)].rgb);
      moments += w * vec2(l, l * l);
      sum_w += w;
    }
  }
  moments /= max(sum_w, 1e-6);
  // Fewer frames behind it: more uncertain (SVGF's boost of the spatial estimate).
  float boost = kDenoiseShortHistory / max(moments_in.p[index].z, 1.0);
  accum_out.p[index] = vec4(centre.rgb, max(moments.y - moments.x * moments.x, 0.0) * boost);
}
