// The stored form of a reservoir: 16 bytes per pixel for the reservoir buffers, packed from and
// unpacked to the working Reservoir (reservoir.h). Layout and precision:
//   light_age    low 24 bits: light index (kPackedNoLight: empty); high 8 bits: the sample's age
//                in frames, saturating at 255. 24 bits hold every light a scene can bind: 2^24
//                GpuLights of 64 bytes are 1 GiB, beyond the 128 MiB maxStorageBufferRange.
//   uv           2 x 16-bit unorm point on the light (error <= 0.5 / 65535)
//   W            32-bit float contribution weight (exact)
//   m_target     low 16 bits: M rounded to an integer in [0, 65535]; high 16 bits: p̂(y) as half
//                (relative error <= 2^-11; saturates at 65504; a positive p̂ never packs to 0)
// weight_sum is not stored: a stored reservoir is always finalized, so only W is needed.
#ifndef LANTERN_SHARED_RESERVOIR_PACK_H
#define LANTERN_SHARED_RESERVOIR_PACK_H

#include "shared/common_math.h"
#include "shared/lang.h"
#include "shared/reservoir.h"

LANTERN_BEGIN_SHARED

struct PackedReservoir {
  uint light_age;
  uint uv;
  float W;
  uint m_target;
};
LANTERN_STATIC_SIZE(PackedReservoir, 16);

LANTERN_CONST float kPackedMaxM = 65535.0f;
LANTERN_CONST uint kPackedLightMask = 0xffffffu;
LANTERN_CONST uint kPackedNoLight = 0xffffffu;  // the 24-bit form of kInvalidLight
LANTERN_CONST uint kPackedMaxLights = 0xffffffu;  // light indices must stay below this
                                                  // (kEnvironmentLight = kPackedMaxLights - 1)
LANTERN_CONST uint kPackedMaxAge = 255u;  // Reservoir.age's 8 bits (age and visibility flag)
LANTERN_CONST float kHalfMax = 65504.0f;

// Half bits of a non-negative p̂: saturating, and never 0 for a positive input (0 would make the
// sample look impossible in the MIS weights of the pixel that stored it).
LANTERN_FUNC uint pack_target_pdf_half(float target_pdf) {
  float p = min(finite_positive_or_zero(target_pdf), kHalfMax);
  uint bits = packHalf2x16(vec2(p, 0.0f)) & 0xffffu;
  return (p > 0.0f && bits == 0u) ? 1u : bits;
}

LANTERN_FUNC PackedReservoir reservoir_pack(Reservoir r) {
  PackedReservoir p;
  float w = finite_positive_or_zero(r.W);
  bool empty = r.selected.light_index >= kPackedMaxLights || w == 0.0f;
  uint light = empty ? kPackedNoLight : r.selected.light_index;
  p.light_age = light | (min(r.age, kPackedMaxAge) << 24u);
  p.uv = packUnorm2x16(vec2(r.selected.u, r.selected.v));
  p.W = empty ? 0.0f : w;
  uint m = uint(min(finite_positive_or_zero(r.M), kPackedMaxM) + 0.5f);
  p.m_target = min(m, 65535u) | (pack_target_pdf_half(r.selected.target_pdf) << 16u);
  return p;
}

// M of a stored reservoir (the confidence: how many candidates stand behind its sample).
LANTERN_FUNC float packed_reservoir_m(PackedReservoir p) { return float(p.m_target & 0xffffu); }

// The unpacked reservoir is finalized: weight_sum is set to W * p̂ so that merging and
// re-finalizing give the same W.
LANTERN_FUNC Reservoir reservoir_unpack(PackedReservoir p) {
  Reservoir r;
  vec2 uv = unpackUnorm2x16(p.uv);
  float target_pdf = unpackHalf2x16(p.m_target >> 16u).x;
  uint light = p.light_age & kPackedLightMask;
  r.selected = light_sample_make(light == kPackedNoLight ? kInvalidLight : light, uv, target_pdf);
  r.W = finite_positive_or_zero(p.W);
  r.weight_sum = reservoir_weight_guard(r.W * r.selected.target_pdf);
  r.M = packed_reservoir_m(p);
  r.age = p.light_age >> 24u;
  return r;
}

LANTERN_END_SHARED

#endif
