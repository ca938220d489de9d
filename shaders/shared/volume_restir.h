// ReSTIR for the media (lighting/volume/volume_restir.h): the reservoirs of in-scattering along
// each pixel's camera ray, their push constants and streams, shared by the C++ passes and
// shaders/volume/volume_restir_*.comp.
//
// A sample y = (medium, t, light, uv): the scattering point at distance t along the pixel's
// camera ray inside volume `medium`, lit by light sample (light, uv) (shared/light_eval.h's
// measure; kEnvironmentLight: uv is the map coordinate of a direction). Reuse keeps the light
// point. Between neighbours of one frame it keeps t too (the same camera; a shift whose Jacobian
// is 1), weighed by VolumeRestirPush.bias_correction's mode. Between frames t follows the world
// point (volume_temporal_shift: Jacobian a, the cosine between the two rays), weighed by the
// balance heuristic with that Jacobian. The
// target p̂ at a pixel is the unshadowed in-scattering made cheap: luminance(phase Le G) x the
// cell's majorant extinction x the medium's scattering share x exp(-guide (t - t_enter)) (the
// volume's guide extinction from where the ray enters it; lib/volume_scatter.glsl
// volume_sample_target). The final shading uses the true density,
// the unbiased transmittances and the shadow ray, so the estimate stays unbiased (Lin, Wyman &
// Yuksel 2021: a cheap target inside resampling adds no bias).
#ifndef LANTERN_SHARED_VOLUME_RESTIR_H
#define LANTERN_SHARED_VOLUME_RESTIR_H

#include "shared/common_math.h"
#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// One pixel's reservoir (std430). An empty one has light == kInvalidLight and W = 0; indices
// are stored as integers (small ones would be denormals as float bits, which a CPU device may
// flush to zero).
struct VolumeReservoir {
  vec4 scatter;  // x: t (m); yz: the light sample's uv; w: W (contribution weight)
  vec4 ray;      // xyz: the owning pixel's unit camera ray; w: where it ends (surface or far)
  float M;       // confidence
  float target;  // p̂ at its own pixel
  uint light;    // light index, kEnvironmentLight, or kInvalidLight (empty)
  uint medium;   // volume index
};
LANTERN_STATIC_SIZE(VolumeReservoir, 48);

// Push constants of volume.restir_initial and volume.restir_spatial.
struct VolumeRestirPush {
  uint width;
  uint height;
  uint candidates;  // initial (distance, light) candidates per pixel
  uint flags;       // kVolumeRestirFlag*
  uint neighbours;  // spatial neighbours (0: no spatial reuse)
  float radius;     // spatial disk radius, pixels
  float m_cap;      // temporal history's confidence cap
  uint bias_correction;  // spatial MIS weights: a kBiasCorrection* (shared/reservoir_mis.h)
};
LANTERN_STATIC_SIZE(VolumeRestirPush, 32);

// The temporal shift of a media sample: the history sample at distance t on last frame's camera
// ray prev_origin + t prev_dir is carried by its medium's motion since last frame (`motion`,
// GpuVolume.motion: identity for a still medium) and moved to the point of this frame's ray
// origin + t' dir nearest where it went: with o' + t d' the moved ray (o' = motion prev_origin,
// d' = motion's linear part prev_dir), t' = a t + b, a = dot(d', dir), b = dot(o' - origin, dir).
// An affine bijection between the rays' distances (inverse (t' - b) / a) with Jacobian
// dt'/dt = a. It keeps the scattering point in the medium where keep-t (t' = t) would move it by
// the camera's displacement and lose the medium's. The shift is vec2(a, b); reuse needs
// a >= kVolumeShiftMinCos.
LANTERN_CONST float kVolumeShiftMinCos = 0.5f;

LANTERN_FUNC vec2 volume_temporal_shift(mat4 motion, vec3 prev_origin, vec3 prev_dir, vec3 origin,
                                        vec3 dir) {
  vec3 moved_origin = vec3(motion * vec4(prev_origin, 1.0f));
  vec3 moved_dir = mat3(motion) * prev_dir;
  return vec2(dot(moved_dir, dir), dot(moved_origin - origin, dir));
}

// History distance t -> this frame's.
LANTERN_FUNC float volume_shift_forward(vec2 shift, float t) { return shift.x * t + shift.y; }

// This frame's distance t -> the history ray's (shift.x >= kVolumeShiftMinCos).
LANTERN_FUNC float volume_shift_back(vec2 shift, float t) { return (t - shift.y) / shift.x; }

LANTERN_CONST uint kVolumeRestirFlagHistoryValid = 1u;  // last frame's reservoirs may be reused
LANTERN_CONST uint kVolumeRestirMaxCandidates = 64u;
LANTERN_CONST uint kVolumeRestirMaxNeighbours = 6u;

// Random streams (frame_rng's pass).
LANTERN_CONST uint kVolumeRngRestirInitial = 0x564f4du;
LANTERN_CONST uint kVolumeRngRestirSpatial = 0x564f4eu;
LANTERN_CONST uint kVolumeRngRestirShade = 0x564f4fu;

LANTERN_END_SHARED

#endif
