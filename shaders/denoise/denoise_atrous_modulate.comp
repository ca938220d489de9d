// denoise.atrous_modulate: the last à-trous step (denoise_atrous.comp) and the result back to
// radiance in the same pass (denoise_remodulate, as denoise.modulate), so the filtered
// illumination is not written out and read back.
// Reads: accum_in (rgb illumination, a variance), guide, luminance_in (when it is also the first
// step: atrous 1), hdr_in (raw radiance, for pass-through pixels), gbuffer
// position/albedo_roughness/emission_metallic. Writes: hdr_out (linear radiance, alpha 1).
// History: none. Dispatch: one thread per pixel pair (atrous_pair), 8x8 groups.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "denoise/denoise_atrous.glsl"

layout(binding = 3, rgba16f) readonly uniform image2D gbuffer_albedo_roughness;
layout(binding = 5, rgba32f) readonly uniform image2D gbuffer_emission_metallic;
layout(std430, binding = 6) readonly buffer HdrIn { vec4 p[]; } hdr_in;
layout(std430, binding = 7) writeonly buffer HdrOut { vec4 p[]; } hdr_out;

void main() {
  ivec2 p0;
  bool has_second;
  if (!atrous_pair(p0, has_second)) return;
  vec4 result[2];
  atrous_step_pair(p0, has_second, result);
  [[unroll]] for (int k = 0; k < 2; ++k) {
    if (k == 1 && !has_second) break;
    ivec2 pixel = p0 + ivec2(k * int(push.step), 0);
    uint index = denoise_index(pixel);
    vec3 rgb = denoise_remodulate(imageLoad(gbuffer_position, pixel).w,
                                  imageLoad(gbuffer_emission_metallic, pixel).rgb,
                                  imageLoad(gbuffer_albedo_roughness, pixel).rgb,
                                  hdr_in.p[index].rgb, result[k].rgb);
    hdr_out.p[index] = vec4(rgb, 1.0);
  }
}
