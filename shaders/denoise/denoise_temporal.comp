// denoise.temporal: demodulates this frame's raw radiance (less an emitter's emission) by the
// surface's albedo, reprojects last frame's denoised illumination and luminance moments along the
// motion vector (bilinear over the 2x2 previous pixels, each kept only when it passes ReSTIR's
// surface-similarity test, restir_surfaces_similar: a camera cut or a disocclusion leaves no
// history; so does a footprint less than kDenoiseMinHistoryFootprint of which passes), clamps a
// firefly against the history's mean + firefly x sigma (where the history cannot judge, against
// push.neighbour_clamp x the second brightest of its 8 neighbours on its own surface, the one there
// if only one is, or the brightest of all 8 where none is; a long history that has seen only black
// takes the sample unclamped into its luminance moments), holds the colour history near its short
// luminance mean (push.antilag: a light that changes is followed), and blends (alpha = max(c / (c +
// (length - 1) x the history's mean confidence), push.color_alpha): 1 / history length when every
// frame is worth the same, else each weighs by the integrator's M; the luminance moments keep 1 /
// length). With push.repay > 0 the light a clamp takes is owed to the pixel, not dropped: each
// frame pays back push.repay of what is owed, as far as the clamp's limit leaves room (a still
// pixel's mean keeps the clamped light; a new sample never exceeds the limit). An emitter is
// filtered for the light it reflects and only among emitters (its neighbour clamp compares
// emitters; without kDenoiseFlagFilterEmitters it passes through: denoise_passthrough); the sky
// passes through unless push.sky_distance > 0 (levels with volumes): then a sky pixel is a surface
// that far along its view ray, facing the camera, albedo 1, reprojected as that point.
// Reads: hdr_in, gbuffer position/normal/albedo_roughness/emission_metallic/ids/motion,
// surface_keys_history, color_history, moments_history, frame constants (prev_view_proj),
// confidence_in (with kDenoiseFlagConfidence: the integrator's PackedReservoirs, their M),
// stable_history (with kDenoiseFlagStableHistory), owed_history (with kDenoiseFlagOwedHistory).
// Writes: surface_keys_out (this frame's "denoise.surface_keys": each pixel's RestirSimilarityKey,
// what the reprojection test reads), accum_out (rgb illumination, a:
// temporal variance; "denoise.color", next frame's history), moments_out ("denoise.moments": x, y
// luminance moments, z history length, w mean confidence),
// guide_out ("denoise.guide", denoise_common.glsl), stable_reprojected_out (push.stabilize > 0:
// last frame's stabilised output at this pixel through the same taps as the colour history; a:
// the share of the blend denoise.atrous_modulate gives it, 0 where there is none), owed_out
// (push.repay > 0: "denoise.owed", rgb illumination the clamps took and have not given back).
// History: "denoise.surface_keys", "denoise.color", "denoise.moments" (and "denoise.stable",
// "denoise.owed") of last frame; without kDenoiseFlagHistoryValid (kDenoiseFlagStableHistory,
// kDenoiseFlagOwedHistory) the history bindings are stand-ins and are not read.
// Dispatch: one thread per pixel, lib/pixel_groups.glsl groups.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "denoise/denoise_common.glsl"
#include "shared/reservoir_pack.h"
#include "shared/restir.h"

#include "lib/scene_buffers.glsl"

layout(binding = PASS_BINDING(0), rgba32f) readonly uniform image2D gbuffer_position;
layout(binding = PASS_BINDING(1), rgba32f) readonly uniform image2D gbuffer_normal;
layout(binding = PASS_BINDING(2), rgba16f) readonly uniform image2D gbuffer_albedo_roughness;
layout(binding = PASS_BINDING(3), rgba32f) readonly uniform image2D gbuffer_emission_metallic;
layout(binding = PASS_BINDING(4), rgba32ui) readonly uniform uimage2D gbuffer_ids;
layout(binding = PASS_BINDING(5), rgba32f) readonly uniform image2D gbuffer_motion;
layout(std430, binding = PASS_BINDING(6)) readonly buffer HdrIn { vec4 p[]; } hdr_in;
layout(std430, binding = PASS_BINDING(7)) writeonly buffer SurfaceKeysOut {
  RestirSimilarityKey k[];
} surface_keys_out;
layout(binding = PASS_BINDING(8)) uniform utextureBuffer surface_keys_history;
layout(binding = PASS_BINDING(9)) uniform utextureBuffer color_history;
layout(binding = PASS_BINDING(10)) uniform utextureBuffer moments_history;
layout(std430, binding = PASS_BINDING(11)) writeonly buffer AccumOut { vec4 p[]; } accum_out;
layout(std430, binding = PASS_BINDING(12)) writeonly buffer MomentsOut { vec4 p[]; } moments_out;
layout(std430, binding = PASS_BINDING(13)) writeonly buffer GuideOut { vec4 p[]; } guide_out;
layout(std430, binding = PASS_BINDING(14)) readonly buffer ConfidenceIn {
  PackedReservoir r[];
} confidence_in;
layout(binding = PASS_BINDING(15)) uniform utextureBuffer stable_history;
layout(std430, binding = PASS_BINDING(16)) writeonly buffer StableReprojectedOut {
  vec4 p[];
} stable_reprojected_out;
layout(binding = PASS_BINDING(17)) uniform utextureBuffer owed_history;
layout(std430, binding = PASS_BINDING(18)) writeonly buffer OwedOut { vec4 p[]; } owed_out;

// Neighbour q's demodulated luminance in this frame, for the neighbour clamp of a pixel at x
// (shading normal n, `distance` from the camera) that is an emitter or not (`emitter`): -1 where
// it does not count (outside the image, passed through, of the other kind: denoise_record).
// `same_surface`: q shows the pixel's own surface, within two of the à-trous depth stops
// (push.phi_depth x distance) of its tangent plane and its normal within ReSTIR's normal
// threshold (push.similarity.y) of n.
float neighbour_luminance(ivec2 q, bool emitter, vec3 x, vec3 n, float distance,
                          out bool same_surface) {
  same_surface = false;
  if (!denoise_inside(q)) return -1.0;
  vec4 position = imageLoad(gbuffer_position, q);
  vec3 emission = imageLoad(gbuffer_emission_metallic, q).rgb;
  if (denoise_passthrough(position.w, emission)) return -1.0;
  if (denoise_is_emitter(position.w, emission) != emitter) return -1.0;
  vec3 nq = oct_decode(imageLoad(gbuffer_normal, q).xy);
  same_surface = abs(dot(n, position.xyz - x)) <= 2.0 * push.phi_depth * distance &&
                 dot(n, nq) >= push.similarity.y;
  return luminance(denoise_demodulate(position.w, emission,
                                      imageLoad(gbuffer_albedo_roughness, q).rgb,
                                      hdr_in.p[denoise_index(q)].rgb));
}

// The luminance that vouches for a sample `l` where the history cannot judge it: the second
// brightest among the 8 neighbours on the pixel's own surface (at x, normal n, `distance` from
// the camera: neighbour_luminance), the brightest where only one is on it, else the brightest of
// all 8; negative when none counts. A pole or a ledge one pixel wide is judged by the pole's or
// the ledge's pixels, not by the lit wall beside it, whose light let the pole's heavy samples
// through (night_market's silhouettes: README "The neighbours on the pixel's own surface"). Two
// neighbours, not one: ReSTIR's heavy samples come in pairs and clusters where reuse spread one
// over a few pixels, and by the brightest neighbour each of two side by side vouched for the
// other (night_market: denoised relMSE -13 to -34% on seeds 1-6, README "Two neighbours vouch
// for a sample"). The 4 beside the pixel come first, then the corners, and the reads stop once
// the vouching luminance admits the sample (push.neighbour_clamp x it >= l). Read only where the
// history cannot judge (a disocclusion, the first frames after a cut, a history that has seen
// only black: night_market's shadows) and the sample is lit (a black one is never clamped).
float vouching_neighbour(ivec2 pixel, bool emitter, float l, vec3 x, vec3 n, float distance) {
  const ivec2 kOrder[8] = ivec2[8](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1),
                                   ivec2(-1, -1), ivec2(1, -1), ivec2(-1, 1), ivec2(1, 1));
  float brightest = -1.0;  // on the surface
  float second = -1.0;     // on the surface
  float any = -1.0;
  for (int t = 0; t < 8 && push.neighbour_clamp * second < l; ++t) {
    bool same_surface;
    float lq = neighbour_luminance(pixel + kOrder[t], emitter, x, n, distance, same_surface);
    any = max(any, lq);
    if (same_surface) {
      second = max(second, min(brightest, lq));
      brightest = max(brightest, lq);
    }
  }
  return second >= 0.0 ? second : brightest >= 0.0 ? brightest : any;
}

// A sample's luminance moments (l, l^2), finite for every finite l (kDenoiseMaxMomentLuminance).
vec2 luminance_moments(float l) {
  float m = min(l, kDenoiseMaxMomentLuminance);
  return vec2(m, m * m);
}

void main() {
  ivec2 pixel;
  if (!denoise_pixel(pixel)) return;
  uint index = denoise_index(pixel);
  vec4 position = imageLoad(gbuffer_position, pixel);
  vec3 radiance = denoise_finite(hdr_in.p[index].rgb);
  vec4 emission_metallic = imageLoad(gbuffer_emission_metallic, pixel);
  if (denoise_passthrough(position.w, emission_metallic.rgb)) {
    surface_keys_out.k[index] = restir_similarity_key(restir_surface_sky());
    accum_out.p[index] = vec4(radiance, 0.0);
    moments_out.p[index] = vec4(0.0);
    guide_out.p[index] = denoise_guide_passthrough();
    if (push.stabilize > 0.0) stable_reprojected_out.p[index] = vec4(0.0);
    if (push.repay > 0.0) owed_out.p[index] = vec4(0.0);
    return;
  }
  const bool emitter = denoise_is_emitter(position.w, emission_metallic.rgb);
  vec4 normals = imageLoad(gbuffer_normal, pixel);
  vec4 albedo_roughness = imageLoad(gbuffer_albedo_roughness, pixel);
  uint material = imageLoad(gbuffer_ids, pixel).y;
  vec3 n = oct_decode(normals.xy);
  vec3 ng = oct_decode(normals.zw);
  // xy: from this frame's sample to last frame's (the reprojection below); zw: the point's own
  // motion, without the jitter step (the stabilisation's stillness).
  vec4 motions = imageLoad(gbuffer_motion, pixel);
  vec2 motion = motions.xy;
  // Before a filtered sky pixel takes its stand-in surface below (albedo 1, as demodulated here).
  vec3 illumination =
      denoise_demodulate(position.w, emission_metallic.rgb, albedo_roughness.rgb, radiance);
  bool sky = gbuffer_is_sky(position.w);
  if (sky) {
    // A filtered sky pixel (levels with volumes): a surface push.sky_distance along the view
    // ray, facing the camera, albedo 1; its motion is that point's reprojection.
    FrameConstants fc = frame_constants.frame;
    vec3 dir = env_camera_ray_dir(fc, uvec2(pixel));
    vec3 far_point = fc.camera_position.xyz + dir * push.sky_distance;
    position = vec4(far_point, (fc.view_proj * vec4(far_point, 1.0)).w);
    n = -dir;
    ng = -dir;
    albedo_roughness = vec4(1.0);
    material = 0xffffffffu;
    vec4 prev_clip = fc.prev_view_proj * vec4(far_point, 1.0);
    motion = prev_clip.w > 0.0
                 ? (prev_clip.xy / prev_clip.w * 0.5 + 0.5) * vec2(push.width, push.height) -
                       (vec2(pixel) + 0.5)
                 : vec2(uintBitsToFloat(0x7f800000u));  // behind last frame's camera
  }
  RestirSurface surface = restir_surface_pack(position, n, ng, albedo_roughness.rgb,
                                              albedo_roughness.a, sky ? 0.0 : emission_metallic.a,
                                              0.0, material);
  RestirSimilarityKey key = restir_similarity_key(surface);
  surface_keys_out.k[index] = key;
  const vec4 guide = denoise_guide(position.xyz - frame_constants.frame.camera_position.xyz, n);
  guide_out.p[index] = guide;
  float l = luminance(illumination);

  // Last frame's history at the reprojected position: bilinear weights of the similar taps.
  vec3 history_color = vec3(0.0);
  vec3 history_stable = vec3(0.0);  // last frame's stabilised output (kDenoiseFlagStableHistory)
  const bool stable = (push.flags & kDenoiseFlagStableHistory) != 0u;
  vec4 history_moments = vec4(0.0);  // x, y moments, z length, w mean confidence
  const bool owed_history_valid = (push.flags & kDenoiseFlagOwedHistory) != 0u;
  vec3 owed = vec3(0.0);  // the light last frame's clamps left owed here (push.repay > 0)
  float weight_sum = 0.0;
  if ((push.flags & kDenoiseFlagHistoryValid) != 0u && is_finite(motion.x) && is_finite(motion.y)) {
    vec2 p = vec2(pixel) + motion;  // previous pixel centre minus 0.5
    ivec2 base = ivec2(floor(p));
    vec2 f = p - vec2(base);
    float expected_depth = (frame_constants.frame.prev_view_proj * vec4(position.xyz, 1.0)).w;
    for (int t = 0; t < 4; ++t) {
      ivec2 o = ivec2(t & 1, t >> 1);
      float w = (o.x == 0 ? 1.0 - f.x : f.x) * (o.y == 0 ? 1.0 - f.y : f.y);
      ivec2 q = base + o;
      if (w <= 0.0 || !denoise_inside(q)) continue;
      uint qi = denoise_index(q);
      if (!restir_keys_similar(key, expected_depth, restir_similarity_key_fetch(surface_keys_history, qi),
                               push.similarity)) {
        continue;
      }
      history_color += w * vec4_fetch(color_history, qi).rgb;
      if (stable) history_stable += w * vec4_fetch(stable_history, qi).rgb;
      if (owed_history_valid) owed += w * vec4_fetch(owed_history, qi).rgb;
      history_moments += w * vec4_fetch(moments_history, qi);
      weight_sum += w;
    }
  }

  // Mostly hidden last frame: a disocclusion, no history (kDenoiseMinHistoryFootprint).
  const bool has_history = weight_sum >= kDenoiseMinHistoryFootprint;
  if (has_history) {
    history_color /= weight_sum;
    history_stable /= weight_sum;
    history_moments /= weight_sum;
    owed /= weight_sum;
  } else {
    owed = vec3(0.0);  // a disocclusion or a cut: what was owed here is dropped with the history
  }
  // What denoise.atrous_modulate's stabilisation blends with, and how much (a): all of it on a
  // still point, less as the point moves, none from a pixel on (each frame's bilinear resampling
  // would blur a moving view: night_market walking, seeds 1-3, denoised relMSE +1.7-3.9% at
  // stabilize 0.5 with a = 1, +0.2-2.7% with this), nothing where there is no history, and a
  // share growing with the history's length (kDenoiseStabilizeFullHistory). The point's own
  // motion (zw), not xy's jittered-sample step: a still view rendered with jitter (below output
  // size) is still.
  if (push.stabilize > 0.0) {
    vec2 own_motion = sky ? motion : motions.zw;
    bool known = is_finite(own_motion.x) && is_finite(own_motion.y);
    float still = has_history && stable && known ? clamp(1.0 - length(own_motion), 0.0, 1.0) : 0.0;
    float grown = (history_moments.z + 1.0 - kDenoiseShortHistory) /
                  (kDenoiseStabilizeFullHistory - kDenoiseShortHistory);
    stable_reprojected_out.p[index] = vec4(history_stable, still * clamp(grown, 0.0, 1.0));
  }
  // Anti-firefly (biased, bounded): a new sample far above what this pixel has seen is clamped to
  // the history's mean + firefly x sigma. A history that is missing, short or has seen nothing
  // but black is no evidence (clamping to its mean of 0 would keep the pixel black for as long
  // as its history lasts: a light switched on in a dark room, a penumbra pixel whose first
  // samples were all shadowed); there the sample is clamped to neighbour_clamp x what its
  // neighbours in this frame vouch for instead (vouching_neighbour), which a lit region passes
  // and a lone heavy-tailed sample (ReSTIR's, next to a small bright light) does not.
  bool history_judges = has_history && history_moments.z >= kDenoiseShortHistory &&
                        history_moments.x > 0.0;
  float limit = uintBitsToFloat(0x7f800000u);
  if (history_judges && push.firefly > 0.0) {
    float sigma = sqrt(max(history_moments.y - history_moments.x * history_moments.x, 0.0));
    limit = history_moments.x + push.firefly * sigma;
  } else if (!history_judges && push.neighbour_clamp > 0.0 && l > 0.0) {
    float neighbour =
        vouching_neighbour(pixel, emitter, l, position.xyz, n, denoise_guide_distance(guide));
    if (neighbour >= 0.0) limit = push.neighbour_clamp * neighbour;
  }
  // What the luminance moments take: the clamped sample, except on a long history that has seen
  // only black, whose moments take it unclamped. There a lone sample is still clamped in the
  // colour, but one that comes back finds a history that judges it (mean + firefly x sigma)
  // instead of the neighbours again: a lit pixel among dark ones (a thin lit edge, a penumbra
  // pixel that ReSTIR keeps lighting) was held black for as long as it stayed lit
  // (cornell_lights: a pixel lit 12 frames in a row stayed 0.000).
  const bool black_history = has_history && history_moments.z >= kDenoiseShortHistory &&
                             !(history_moments.x > 0.0);
  float l_moments = l;
  vec3 taken = vec3(0.0);
  if (l > limit) {
    vec3 kept = limit > 0.0 ? illumination * (limit / l) : vec3(0.0);
    taken = illumination - kept;
    illumination = kept;
    l = limit;
  }
  // Repay: push.repay of what is owed, at most up to the limit, joins this frame's sample (its
  // moments too, so the history judges the next sample by what the pixel shows; a black sample the
  // history cannot judge has no limit, and holding it to the neighbours' traded the mean for error
  // on night_market: README "Two neighbours vouch for a sample"); what a clamp took now is owed
  // from the next frame on. The temporal accumulation averages the frames' samples, so light given
  // back a few frames later counts in the pixel's mean (as much as the sample it came from where
  // every frame weighs alike). Owed luminance is capped at kDenoiseMaxMomentLuminance, so an absurd
  // sample cannot make it infinite.
  if (push.repay > 0.0) {
    float owed_luminance = luminance(owed);
    float repaid = min(owed_luminance * push.repay, max(limit - l, 0.0));
    if (repaid > 0.0) {  // then owed_luminance > 0 too
      vec3 given = owed * (repaid / owed_luminance);
      illumination += given;
      owed = max(owed - given, vec3(0.0));
      l += repaid;
      l_moments = max(l_moments, l);
    }
    owed += taken;
    owed_luminance = luminance(owed);
    if (owed_luminance > kDenoiseMaxMomentLuminance) {
      owed *= kDenoiseMaxMomentLuminance / owed_luminance;
    }
    owed_out.p[index] = vec4(owed, 0.0);
  }
  if (!black_history) l_moments = l;

  // This frame's confidence: the integrator's M (ReSTIR: the candidates behind the pixel's
  // sample, 8 in a first frame, hundreds once temporal reuse has settled), else 1 per frame.
  float confidence = (push.flags & kDenoiseFlagConfidence) != 0u
                         ? max(packed_reservoir_m(confidence_in.r[index]), 1.0)
                         : 1.0;
  vec3 color = illumination;
  vec2 moments = luminance_moments(l);
  float frames = 1.0;
  float mean_confidence = confidence;
  if (has_history) {
    float history_length = history_moments.z;
    frames = min(history_length + 1.0, push.max_history);
    // Antilag: the colour history averages up to max_history frames, the luminance moments about
    // 2 / moments_alpha; where light changes (a lamp dims, a shadow moves in) the short mean
    // leaves the long one behind. The colour history is held within `antilag` standard errors
    // of the short mean (its samples' sigma over the root of its frames), so the image follows
    // within the short window instead of lagging over the long one; on a still view the band
    // rarely binds. An all-black colour history is left alone (it has no colour to scale).
    if (push.antilag > 0.0 && history_moments.z >= kDenoiseShortHistory) {
      float short_mean = history_moments.x;
      float sigma = sqrt(max(history_moments.y - short_mean * short_mean, 0.0));
      float short_frames = min(history_moments.z, 2.0 / push.moments_alpha - 1.0);
      float band = push.antilag * sigma / sqrt(short_frames);
      float long_mean = luminance(history_color);
      float held = clamp(long_mean, max(short_mean - band, 0.0), short_mean + band);
      if (long_mean > 0.0) history_color *= held / long_mean;
    }
    // Each frame's pixel weighs by its confidence: a = c / (c + (frames - 1) x the history's mean
    // confidence), floored by color_alpha; the mean follows c over the same frames. With equal
    // confidences this is 1 / frames; ReSTIR's warm-up frames (few candidates, mostly empty
    // picks in hard-to-light places) no longer hold the average down for the next 30 frames, and
    // one frame of low confidence weighs little without shrinking the history's worth.
    float history_confidence = history_moments.w > 0.0 ? history_moments.w : confidence;
    float a = max(confidence / (confidence + (frames - 1.0) * history_confidence),
                  push.color_alpha);
    mean_confidence = mix(history_confidence, confidence, 1.0 / frames);
    float am = max(1.0 / frames, push.moments_alpha);
    color = mix(history_color, illumination, a);
    moments = mix(history_moments.xy, luminance_moments(l_moments), am);
  }
  float variance = max(moments.y - moments.x * moments.x, 0.0);
  accum_out.p[index] = denoise_record(color, variance, emitter);
  moments_out.p[index] = vec4(moments, frames, mean_confidence);
}
