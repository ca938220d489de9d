// denoise.modulate: the filtered illumination back to radiance: albedo demodulation x
// illumination (the same factor denoise.temporal divided by; 1 for a filtered sky pixel);
// emitters and an unfiltered sky (denoise_passthrough) keep the raw radiance.
// Reads: accum_in (rgb illumination), hdr_in (raw radiance, for the sky), gbuffer
// position/albedo_roughness/emission_metallic. Writes: hdr_out (linear radiance, alpha 1).
// History: none. Dispatch: one thread per pixel, 8x8 groups.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "denoise/denoise_common.glsl"

layout(binding = 0, rgba32f) readonly uniform image2D gbuffer_position;
layout(binding = 1, rgba16f) readonly uniform image2D gbuffer_albedo_roughness;
layout(binding = 2, rgba32f) readonly uniform image2D gbuffer_emission_metallic;
layout(std430, binding = 3) readonly buffer AccumIn { vec4 p[]; } accum_in;
layout(std430, binding = 4) readonly buffer HdrIn { vec4 p[]; } hdr_in;
layout(std430, binding = 5) writeonly buffer HdrOut { vec4 p[]; } hdr_out;

void main() {
  ivec2 pixel;
  if (!denoise_pixel(pixel)) return;
  uint index = denoise_index(pixel);
  vec3 rgb;
  if (denoise_passthrough(imageLoad(gbuffer_position, pixel).w,
                          imageLoad(gbuffer_emission_metallic, pixel).rgb)) {
    rgb = denoise_finite(hdr_in.p[index].rgb);
  } else {
    vec3 albedo = denoise_albedo(imageLoad(gbuffer_position, pixel).w,
                                 imageLoad(gbuffer_albedo_roughness, pixel).rgb);
    rgb = denoise_demodulation(albedo) * accum_in.p[index].rgb;
  }
  hdr_out.p[index] = vec4(denoise_finite(rgb), 1.0);
}
