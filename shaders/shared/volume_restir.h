// ReSTIR for the media (lighting/volume/volume_restir.h): the reservoirs of in-scattering along
// each pixel's camera ray, their push constants and streams, shared by the C++ passes and
// shaders/volume/volume_restir_*.comp.
//
// A sample y = (medium, t, light, uv): the scattering point at distance t along the pixel's
// camera ray inside volume `medium`, lit by light sample (light, uv) (shared/light_eval.h's
// measure; kEnvironmentLight: uv is the map coordinate of a direction). Reuse between pixels and
// frames keeps y as it is (the same t on the other pixel's ray, the same light point): a shift
// whose Jacobian is 1 in this measure; the pixels are weighed by their own targets (the balance
// heuristic between frames, VolumeRestirPush.bias_correction's mode between neighbours). The
// target p̂ at a pixel is the unshadowed in-scattering made cheap: luminance(phase Le G) x the
// cell's majorant extinction x the medium's scattering share x exp(-guide (t - t_enter)) (the
// volume's guide extinction from where the ray enters it; lib/volume_scatter.glsl
// volume_sample_target). The final shading uses the true density,
// the unbiased transmittances and the shadow ray, so the estimate stays unbiased (Lin, Wyman &
// Yuksel 2021: a cheap target inside resampling adds no bias).
#ifndef LANTERN_SHARED_VOLUME_RESTIR_H
#define LANTERN_SHARED_VOLUME_RESTIR_H

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

LANTERN_CONST uint kVolumeRestirFlagHistoryValid = 1u;  // last frame's reservoirs may be reused
LANTERN_CONST uint kVolumeRestirMaxCandidates = 64u;
LANTERN_CONST uint kVolumeRestirMaxNeighbours = 6u;

// Random streams (frame_rng's pass).
LANTERN_CONST uint kVolumeRngRestirInitial = 0x564f4du;
LANTERN_CONST uint kVolumeRngRestirSpatial = 0x564f4eu;
LANTERN_CONST uint kVolumeRngRestirShade = 0x564f4fu;

LANTERN_END_SHARED

#endif
