// The denoiser's GPU/CPU facts (lighting/denoise/denoiser.h, shaders/denoise/*.comp): the push
// constants every denoise.* pass receives, its per-pixel records and the albedo demodulation the
// first pass divides by and the last multiplies back (one function, so the two agree exactly).
// The knobs behind the push constants, with when to change each, are
// lighting/denoise/denoise_settings.h.
#ifndef LANTERN_SHARED_DENOISE_H
#define LANTERN_SHARED_DENOISE_H

#include "shared/common_math.h"
#include "shared/lang.h"

LANTERN_BEGIN_SHARED

LANTERN_CONST uint kDenoiseMaxAtrousIterations = 6u;
// History length below which denoise.variance estimates variance spatially (SVGF's 4 frames).
LANTERN_CONST float kDenoiseShortHistory = 4.0f;
// From this history length on, a short history's variance is the smaller of the spatial estimate
// and the pixel's own samples' spread (boosted by kDenoiseShortHistory / frames): a pixel whose
// samples agree, in shadow beside a lit surface of the same normal and material, is no longer taken
// for noise and filtered into its neighbours' light (night_market: the silhouettes of a moving view
// keep pixels at 1-3 frames of history, which held 51-72% of the denoised error; denoised relMSE
// -5/-6/-2% on seeds 1-3 with the means unchanged, README "Where the denoised error sits").
LANTERN_CONST float kDenoiseOwnSpreadHistory = 2.0f;
// The own-spread bound goes no lower than this share of the smaller of the spatial estimate and
// the similar neighbours' own spread: two or three samples can agree by chance (no spread at
// all) among neighbours whose samples do spread, and a pixel taken for noiseless is not filtered.
// cornell_lights' orbiting box leaves such pixels along its edges, whose still-view flicker the
// unfloored bound took over 2x the reference's (2.05/2.24/1.99x on seeds 1-3; 1.67/1.79/1.85x
// with this floor), for night_market's denoised relMSE +1-3% (README "A floor under the own
// spread"). Where the neighbours' samples agree too (a clean edge) the bound stays whole.
LANTERN_CONST float kDenoiseOwnSpreadFloor = 0.05f;
// denoise.temporal keeps a pixel's history only where at least this share of its bilinear
// footprint in the previous frame passed the surface test. With less, the point was mostly
// hidden there (a surface coming out from behind a lantern the camera moved past) and the few
// taps that pass are its neighbours, not it: their light is not its own (night_market, moving
// camera: denoised relMSE -6 to -10% against 256-spp references; still views never see a
// partial footprint).
LANTERN_CONST float kDenoiseMinHistoryFootprint = 0.5f;
// The stabilisation (DenoisePush.stabilize) takes its full share of the blend once a pixel's
// history is this long, none up to kDenoiseShortHistory frames, linearly between: a younger
// history is still converging, and holding its output toward its worse past cost cornell_lights
// at 320x180 12% of denoised relMSE (3% with this ramp).
LANTERN_CONST float kDenoiseStabilizeFullHistory = 8.0f;
// Smallest demodulation factor: keeps dark albedos from amplifying noise (and 0 from dividing).
LANTERN_CONST float kDenoiseMinAlbedo = 0.02f;
// Largest luminance the moments take (denoise.temporal): its square, and mixes of squares, stay
// finite, so a finite but absurd sample (1e30) cannot write Inf into the moments' history.
LANTERN_CONST float kDenoiseMaxMomentLuminance = 1.0e18f;

// DenoisePush.flags.
LANTERN_CONST uint kDenoiseFlagHistoryValid = 1u;  // the graph handed last frame's history
LANTERN_CONST uint kDenoiseFlagSmoothLuminance = 2u;  // denoise.atrous: stop on 3x3 luminance
LANTERN_CONST uint kDenoiseFlagConfidence = 4u;  // denoise.temporal: weigh pixels by their M
// denoise.temporal: last frame's stabilised output ("denoise.stable") is there to reproject.
LANTERN_CONST uint kDenoiseFlagStableHistory = 8u;
// Emitters are filtered for the light they reflect: denoise.temporal takes the G-buffer emission
// (what every integrator adds for the camera's view, exact) off their radiance and the last step
// adds it back. Without it (levels with media, whose camera pass has scaled the emission by a
// sampled transmittance, so radiance - emission is not the reflected light) they pass through.
LANTERN_CONST uint kDenoiseFlagFilterEmitters = 16u;
// denoise.temporal: last frame's owed light ("denoise.owed", push.repay > 0) is there to reproject.
LANTERN_CONST uint kDenoiseFlagOwedHistory = 32u;

// denoise.atrous and denoise.atrous_modulate filter pixel pairs: thread column c of a step with
// tap spacing `step` takes pixels x0 = denoise_atrous_pair_first(c, step) and x0 + step, which
// share 6 of their 9 taps (the columns run in blocks of 2 step: the first `step` of each block
// pair with the next `step`). denoise_atrous_pair_columns threads per row cover every pixel of a
// `width`-pixel row once; an x0 or x0 + step at or past `width` is skipped.
LANTERN_FUNC uint denoise_atrous_pair_columns(uint width, uint step) {
  return (width + 2u * step - 1u) / (2u * step) * step;
}
LANTERN_FUNC uint denoise_atrous_pair_first(uint column, uint step) {
  return (column / step) * 2u * step + column % step;
}

struct DenoisePush {
  uint width;
  uint height;
  uint flags;            // kDenoiseFlag*
  uint step;             // denoise.atrous: tap spacing 2^iteration in pixels
  float color_alpha;     // temporal blend floor of the illumination (1/alpha frames of history)
  float moments_alpha;   // temporal blend floor of the luminance moments
  float phi_luminance;   // à-trous luminance edge stop, in standard deviations
  float phi_normal;      // à-trous normal edge stop: weight = max(0, dot(n, nq))^phi_normal
  float phi_depth;       // à-trous depth edge stop: plane distance / camera distance per tap step
  float firefly;         // temporal clamp of the new sample to mean + firefly x sigma (0: off)
  float max_history;     // history length cap (frames)
  float sky_distance;    // > 0 (levels with volumes: the fog before the sky is noisy): sky pixels
                         // are denoised as a surface this far along their view ray, facing the
                         // camera, albedo 1; 0: the sky passes through unfiltered
  vec4 similarity;       // restir_surfaces_similar's thresholds (shared/restir.h) for reprojection
  float neighbour_clamp;  // where the history cannot judge a new sample (none, shorter than
                          // kDenoiseShortHistory or all black): clamp it to this x the second
                          // brightest of its 8 neighbours on its surface in this frame (0: off)
  float antilag;  // denoise.temporal: the colour history is held within this many standard
                  // errors of the luminance moments' short mean (~2 / moments_alpha frames;
                  // 0: off)
  float stabilize;       // denoise.atrous_modulate: weight of last frame's output, reprojected and
                         // held within stabilize_band standard deviations of this frame's (0: off)
  float stabilize_band;  // that band, in the filtered illumination's standard deviations
  float repay;  // denoise.temporal: the share of a pixel's owed light (what its clamps took) given
                // back each frame, never above the clamp's limit (0: off, the light is dropped)
  uint pad0;    // to the struct's std430 stride (its vec4's alignment)
  uint pad1;
  uint pad2;
};
LANTERN_STATIC_SIZE(DenoisePush, 96);

// What illumination is divided by: the surface's albedo (base colour), floored. Radiance =
// factor x illumination; emitters are not filtered, nor is the sky unless sky_distance > 0.
LANTERN_FUNC vec3 denoise_demodulation(vec3 albedo) {
  return max(albedo, vec3(kDenoiseMinAlbedo));
}

LANTERN_END_SHARED

#endif
