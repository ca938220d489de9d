// Shared GLSL of the denoise.* passes (lighting/denoise/denoiser.h): push constants, the
// one-thread-per-pixel mapping, and the G-buffer reads the edge-stopping functions use. Each pass
// declares the G-buffer images it reads and its own buffers from PASS_BINDING(0) on.
#ifndef LANTERN_DENOISE_COMMON_GLSL
#define LANTERN_DENOISE_COMMON_GLSL

#include "shared/color.h"
#include "shared/common_math.h"
#include "shared/denoise.h"
#include "shared/gbuffer.h"

#include "lib/pixel_groups.glsl"
#include "lib/texel_records.glsl"

layout(push_constant) uniform Push { DenoisePush push; };

ivec2 denoise_size() { return ivec2(push.width, push.height); }

bool denoise_pixel(out ivec2 pixel) {
  pixel = ivec2(gl_GlobalInvocationID.xy);
  return pixel.x < int(push.width) && pixel.y < int(push.height);
}

uint denoise_index(ivec2 pixel) { return uint(pixel.y) * push.width + uint(pixel.x); }

bool denoise_inside(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, denoise_size())); }

vec3 denoise_finite(vec3 c) {
  return vec3(is_finite(c.r) ? c.r : 0.0, is_finite(c.g) ? c.g : 0.0, is_finite(c.b) ? c.b : 0.0);
}

// Whether a pixel shows an emitter: a surface (not the sky) whose G-buffer emission is not black.
bool denoise_is_emitter(float view_depth, vec3 emission) {
  return !gbuffer_is_sky(view_depth) && max(emission.r, max(emission.g, emission.b)) > 0.0;
}

// Pixels the denoiser leaves as they are: the sky unless push.sky_distance > 0, and emitters
// unless kDenoiseFlagFilterEmitters. Otherwise an emitter is filtered for the light it reflects
// (its radiance less its emission, denoise_emission): ReSTIR's samples there are as noisy as on
// any surface, and heavier-tailed where emitters meet (night_market's spinners: a face lit by the
// face beside it, 1/d^2 from their shared edge, came out 30x its emission on single pixels);
// its emission itself is exact and never spreads (filtering it spread a value 10^4 above its
// surroundings on cornell_lights into the dark surfaces around it).
bool denoise_passthrough(float view_depth, vec3 emission) {
  if (gbuffer_is_sky(view_depth)) return !(push.sky_distance > 0.0);
  return denoise_is_emitter(view_depth, emission) &&
         (push.flags & kDenoiseFlagFilterEmitters) == 0u;
}

// The part of a filtered pixel's radiance that is not filtered: its G-buffer emission (0 for a
// surface that emits nothing and for a filtered sky pixel, `sky`).
vec3 denoise_emission(bool sky, vec3 emission) { return sky ? vec3(0.0) : emission; }

// The albedo a pixel's radiance is demodulated by: 1 for a filtered sky pixel (`sky`).
vec3 denoise_albedo(bool sky, vec3 gbuffer_albedo) { return sky ? vec3(1.0) : gbuffer_albedo; }

// The 3x3 tent every step filters with (per axis: centre 1/2, neighbours 1/4): the à-trous
// steps at their tap spacing, the centre's variance blur, denoise.variance's smoothed luminance.
const float kDenoiseKernel[2] = float[2](0.5, 0.25);

// A filtered pixel's raw radiance as illumination (denoise.temporal, for the pixel and for the
// neighbours its clamp compares): (radiance - its emission) / the demodulation factor (1 for a
// filtered sky pixel); never negative (an emitter's radiance is its emission plus reflected light,
// up to rounding).
vec3 denoise_demodulate(float view_depth, vec3 emission, vec3 gbuffer_albedo, vec3 raw) {
  const bool sky = gbuffer_is_sky(view_depth);
  return max(denoise_finite(raw) - denoise_emission(sky, emission), vec3(0.0)) /
         denoise_demodulation(denoise_albedo(sky, gbuffer_albedo));
}

// A filtered pixel's illumination back to radiance: its emission + the illumination x the
// demodulation factor denoise_demodulate divided by; `sky` marks a filtered sky pixel (no
// emission, albedo 1: emission and gbuffer_albedo are not read), `emission` may be 0 for a pixel
// that is no emitter (its G-buffer emission is).
vec3 denoise_remodulate_filtered(bool sky, vec3 emission, vec3 gbuffer_albedo, vec3 illumination) {
  return denoise_finite(denoise_emission(sky, emission) +
                        denoise_demodulation(denoise_albedo(sky, gbuffer_albedo)) * illumination);
}

// A denoised pixel back to radiance (denoise.modulate) from its G-buffer values: a pass-through
// pixel (an unfiltered emitter or sky) keeps its raw radiance, a filtered one
// denoise_remodulate_filtered.
vec3 denoise_remodulate(float view_depth, vec3 emission, vec3 gbuffer_albedo, vec3 raw,
                        vec3 illumination) {
  if (denoise_passthrough(view_depth, emission)) return denoise_finite(raw);
  return denoise_remodulate_filtered(gbuffer_is_sky(view_depth), emission, gbuffer_albedo,
                                     illumination);
}

// The edge-stopping guide denoise.temporal writes once per pixel ("denoise.guide", read by
// every tap of denoise.variance and denoise.atrous instead of G-buffer images): xyz the position
// relative to the camera (world axes: the tangent-plane distances are the world's, and its length
// is the distance the edge stops scale with, denoise_guide_distance), w the octahedral shading
// normal (snorm 2x16) as float bits; kDenoiseSky bits for the pass-through pixels (no tap reads
// them). A pixel's kind (emitter or not) is not here: every step that weighs a tap holds the
// tap's record, which carries it (denoise_record).
const uint kDenoiseSky = 0xffffffffu;

vec4 denoise_guide(vec3 from_camera, vec3 n) {
  return vec4(from_camera, uintBitsToFloat(oct_pack_snorm(n)));
}
// The pixel's distance from the camera (a filtered sky pixel: push.sky_distance).
float denoise_guide_distance(vec4 g) { return length(g.xyz); }
vec4 denoise_guide_passthrough() { return vec4(0.0, 0.0, 0.0, uintBitsToFloat(kDenoiseSky)); }
bool denoise_guide_sky(vec4 g) { return floatBitsToUint(g.w) == kDenoiseSky; }
vec3 denoise_guide_normal(vec4 g) { return oct_unpack_snorm(floatBitsToUint(g.w)); }

// The filtered illumination records between denoise.temporal and the last step (rgb
// illumination, a its variance) carry the pixel's kind, in the variance's sign bit (set on an
// emitter, -0 for none; a pass-through pixel's record is a surface's). Light never spreads
// between kinds: an emitter's reflected light, heavy-tailed where emitters meet, would brighten
// the dark surface beside it. Every tap a step weighs is a record it has read anyway, so the kind
// costs no read (the neighbours' guides read for it cost about 1 ms more for the denoiser at
// 320x180 on lavapipe).
const uint kDenoiseSignBit = 0x80000000u;
vec4 denoise_record(vec3 illumination, float variance, bool emitter) {
  return vec4(illumination, uintBitsToFloat(floatBitsToUint(abs(variance)) |
                                            (emitter ? kDenoiseSignBit : 0u)));
}
float denoise_record_variance(vec4 r) { return abs(r.a); }
bool denoise_record_emitter(vec4 r) { return (floatBitsToUint(r.a) & kDenoiseSignBit) != 0u; }
// A neighbour's variance as the variance blur of a centre of kind `emitter` counts it: 0 for the
// other kind (as for a pass-through pixel, whose record holds variance 0).
float denoise_record_variance_as(vec4 r, bool emitter) {
  return denoise_record_emitter(r) == emitter ? abs(r.a) : 0.0;
}

// Edge-stopping weight of a tap with guide q seen from the centre (guide c, normal n, distance
// from the camera depth), times exp(-extra) (the caller has checked the tap is of the centre's
// kind): its distance from the centre's tangent plane relative to phi_depth x depth x spacing,
// and the normals' agreement max(0, n.nq)^phi_normal. One exp per tap: the power is
// exp(phi_normal ln cos) with ln cos = -(x + x^2/2 + x^3/3 + ...), x = 1 - cos, cut after x^3
// (the weight within 0.2% wherever it exceeds 1e-3 at phi_normal 64, and ~0 where the normals
// part: e^-117 at a right angle). exp and pow were the à-trous steps' largest cost on lavapipe
// (three transcendentals per tap).
float denoise_geometry_weight(vec4 c, vec3 n, float depth, vec4 q, float spacing, float extra) {
  float plane = abs(dot(n, q.xyz - c.xyz));
  float x = 1.0 - clamp(dot(n, denoise_guide_normal(q)), 0.0, 1.0);
  float log_cosine = -x * (1.0 + x * (0.5 + x * (1.0 / 3.0)));
  return exp(-plane / (push.phi_depth * depth * spacing + 1e-6) - extra +
             push.phi_normal * log_cosine);
}

#endif
