// denoise.modulate (only without à-trous steps; otherwise the last step, denoise.atrous_modulate,
// does this): the temporal accumulation back to radiance, denoise_remodulate (emission + albedo
// demodulation x illumination; a pass-through pixel keeps the raw radiance).
// Reads: accum_in (rgb illumination), hdr_in (raw radiance, for pass-through pixels), gbuffer
// position/albedo_roughness/emission_metallic. Writes: hdr_out (linear radiance, alpha 1).
// History: none. Dispatch: one thread per pixel, lib/pixel_groups.glsl groups.
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
  vec3 rgb = denoise_remodulate(imageLoad(gbuffer_position, pixel).w,
                                imageLoad(gbuffer_emission_metallic, pixel).rgb,
                                imageLoad(gbuffer_albedo_roughness, pixel).rgb,
                                hdr_in.p[index].rgb, accum_in.p[index].rgb);
  hdr_out.p[index] = vec4(rgb, 1.0);
}
