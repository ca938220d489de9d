// denoise.atrous_modulate: the last à-trous step (denoise_atrous.comp) and the result back to
// radiance in the same pass (denoise_remodulate_filtered, as denoise.modulate), so the filtered
// illumination is not written out and read back.
// Reads: accum_in (rgb illumination, a variance), guide, luminance_in (when it is also the first
// step: atrous 1), hdr_in (raw radiance, for pass-through pixels), gbuffer albedo_roughness
// (filtered pixels), emission_metallic (emitters), position (with push.sky_distance > 0: which
// pixels are the sky), stable_in (push.stabilize > 0: last frame's
// output reprojected, denoise.temporal). Writes: hdr_out (linear radiance, alpha 1), stable_out
// (push.stabilize > 0: the stabilised illumination, "denoise.stable", next frame's history).
// History: "denoise.stable", through denoise.temporal's stable_reprojected_out.
// Dispatch: one thread per pixel pair (atrous_pair), lib/pixel_groups.glsl groups.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "denoise/denoise_atrous.glsl"

layout(binding = 0, rgba32f) readonly uniform image2D gbuffer_position;
layout(binding = 3, rgba16f) readonly uniform image2D gbuffer_albedo_roughness;
layout(binding = 5, rgba32f) readonly uniform image2D gbuffer_emission_metallic;
layout(std430, binding = 6) readonly buffer HdrIn { vec4 p[]; } hdr_in;
layout(std430, binding = 7) writeonly buffer HdrOut { vec4 p[]; } hdr_out;
layout(std430, binding = 8) readonly buffer StableIn { vec4 p[]; } stable_in;
layout(std430, binding = 9) writeonly buffer StableOut { vec4 p[]; } stable_out;

// Temporal stabilisation (push.stabilize > 0): the filtered illumination r blended with last
// frame's output h at this point (reprojected by denoise.temporal; a scales the weight: 1 on a
// still point, 0 where there is no history or the point moved a pixel or more),
// whose luminance is first held within stabilize_band standard deviations of r's (the filter's
// own estimate of what noise r still carries). On a still view r's residual noise changes every
// frame and h averages it further; where the light really changes, r leaves the band and h is
// pulled along with it, lagging by at most the band.
vec3 stabilize(vec4 r, vec4 h) {
  if (!(h.a > 0.0)) return r.rgb;
  float lr = luminance(r.rgb);
  float band = push.stabilize_band * sqrt(denoise_record_variance(r));
  if (!is_finite(band)) return r.rgb;  // no measure of r's noise: r as it is
  float lh = luminance(h.rgb);
  float held = clamp(lh, max(lr - band, 0.0), lr + band);
  vec3 hc = lh > 0.0 ? h.rgb * (held / lh) : r.rgb;
  return mix(r.rgb, hc, push.stabilize * h.a);
}

void main() {
  ivec2 p0;
  bool has_second;
  if (!atrous_pair(p0, has_second)) return;
  vec4 result[2];
  bool passthrough[2];
  atrous_step_pair(p0, has_second, result, passthrough);
  [[unroll]] for (int k = 0; k < 2; ++k) {
    if (k == 1 && !has_second) break;
    ivec2 pixel = p0 + ivec2(k * int(push.step), 0);
    uint index = denoise_index(pixel);
    if (push.stabilize > 0.0) {
      // A pass-through pixel (denoise_passthrough) has no stabilised history (a = 0 from
      // denoise.temporal), so it keeps its result.
      result[k].rgb = stabilize(result[k], stable_in.p[index]);
      stable_out.p[index] = vec4(result[k].rgb, 0.0);
    }
    // Only the reads a pixel's kind needs (the record's kind and the guide's pass-through mark
    // tell it; three G-buffer reads and the raw radiance for every pixel cost ~0.3 ms more at
    // 320x180 on lavapipe): the raw radiance of a pass-through pixel, the albedo of a filtered
    // one, the emission of an emitter, the view depth only where a sky pixel can be filtered.
    vec3 rgb;
    if (passthrough[k]) {
      rgb = denoise_finite(hdr_in.p[index].rgb);
    } else {
      const bool sky =
          push.sky_distance > 0.0 && gbuffer_is_sky(imageLoad(gbuffer_position, pixel).w);
      vec3 emission = !sky && denoise_record_emitter(result[k])
                          ? imageLoad(gbuffer_emission_metallic, pixel).rgb
                          : vec3(0.0);
      vec3 albedo = sky ? vec3(1.0) : imageLoad(gbuffer_albedo_roughness, pixel).rgb;
      rgb = denoise_remodulate_filtered(sky, emission, albedo, result[k].rgb);
    }
    hdr_out.p[index] = vec4(rgb, 1.0);
  }
}
