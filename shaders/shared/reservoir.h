// ReSTIR's reservoir math, shared by GPU passes and CPU tests: streaming weighted selection of
// light samples, merging reservoirs, and the unbiased contribution weight W of generalized RIS
// (Lin et al. 2022) with resampling MIS weights m_i supplied by the caller (reservoir_mis.h).
//
// Convention: every candidate or reservoir enters with weight w_i = m_i * p̂(y_i) * W_i, where p̂ is
// the target function of the pixel doing the resampling, W_i the candidate's contribution weight
// (1 / source pdf for a fresh candidate) and m_i its MIS weight (the m_i of one resampling sum to
// 1). Finalisation then sets W = weight_sum / p̂(y). All weights pass through a guard, so NaN, Inf
// and negative inputs count as zero and the reservoir state stays finite.
#ifndef LANTERN_SHARED_RESERVOIR_H
#define LANTERN_SHARED_RESERVOIR_H

#include "shared/common_math.h"
#include "shared/lang.h"
#include "shared/lights.h"

LANTERN_BEGIN_SHARED

// Largest accepted single weight: a billion of them still sum below FLT_MAX, so weight_sum
// cannot overflow to Inf.
LANTERN_CONST float kMaxReservoirWeight = 1e29f;

// The light index of a sample of the environment map: (u, v) is the map coordinate of its
// direction (shared/environment.h env_uv_to_world_direction), its measure solid angle. Fits the
// packed reservoir's 24-bit index, so light lists must stay below it.
LANTERN_CONST uint kEnvironmentLight = 0xfffffeu;

// A light sample's identity plus its target value at the pixel that owns it.
struct LightSample {
  uint light_index;  // index into the light list, kEnvironmentLight, or kInvalidLight (none)
  float u;           // point on the light: light-type-specific coordinates in [0,1)^2
  float v;
  float target_pdf;  // p̂(y) at the owning pixel (unnormalised target function)
};
LANTERN_STATIC_SIZE(LightSample, 16);

// The working reservoir (registers and tests). Storage uses PackedReservoir (reservoir_pack.h).
struct Reservoir {
  LightSample selected;  // the surviving sample y
  float weight_sum;      // sum of the guarded weights w_i seen so far
  float M;               // confidence: number of candidates (or capped history) it summarises
  float W;               // unbiased contribution weight of `selected`; valid after finalize
  uint age;              // bits 0-5: frames since `selected` was drawn as a fresh candidate
                         // (saturating); bits 6-7: kReservoirVisibilityKnown/Visible
};
LANTERN_STATIC_SIZE(Reservoir, 32);

// Reservoir.age: the age saturates here, and kReservoirVisibilityKnown says restir.shade tested
// `selected` from this pixel's surface, kReservoirVisible that it was unoccluded (visibility
// reuse: a later frame may shade it without a shadow ray). A merge carries the flags with the
// sample it takes; a fresh candidate clears them; restir.spatial clears them on neighbours'
// samples (seen from another surface).
LANTERN_CONST uint kReservoirMaxAge = 63u;
LANTERN_CONST uint kReservoirVisibilityKnown = 64u;
LANTERN_CONST uint kReservoirVisible = 128u;

// uv is clamped to [0,1] (non-finite -> 0) so a bad coordinate can never reach packing.
LANTERN_FUNC float light_sample_coordinate(float x) {
  return is_finite(x) ? clamp(x, 0.0f, 1.0f) : 0.0f;
}

LANTERN_FUNC LightSample light_sample_make(uint light_index, vec2 uv, float target_pdf) {
  LightSample s;
  s.light_index = light_index;
  s.u = light_sample_coordinate(uv.x);
  s.v = light_sample_coordinate(uv.y);
  s.target_pdf = finite_positive_or_zero(target_pdf);
  return s;
}

LANTERN_FUNC Reservoir reservoir_empty() {
  Reservoir r;
  r.selected = light_sample_make(kInvalidLight, vec2(0.0f), 0.0f);
  r.weight_sum = 0.0f;
  r.M = 0.0f;
  r.W = 0.0f;
  r.age = 0u;
  return r;
}

LANTERN_FUNC bool reservoir_has_sample(Reservoir r) {
  return r.selected.light_index != kInvalidLight && r.W > 0.0f;
}

LANTERN_FUNC uint reservoir_age(Reservoir r) {
  return r.age & kReservoirMaxAge;
}
LANTERN_FUNC bool reservoir_visibility_known(Reservoir r) {
  return (r.age & kReservoirVisibilityKnown) != 0u;
}
LANTERN_FUNC bool reservoir_known_visible(Reservoir r) {
  return (r.age & kReservoirVisible) != 0u;
}
// Records shade's verdict (known) or forgets it (known = false).
LANTERN_FUNC void reservoir_set_visibility(LANTERN_INOUT(Reservoir) r, bool known, bool visible) {
  r.age = reservoir_age(r) | (known ? kReservoirVisibilityKnown : 0u) |
          (known && visible ? kReservoirVisible : 0u);
}
// One frame older (history reuse), keeping the visibility flags.
LANTERN_FUNC void reservoir_age_one_frame(LANTERN_INOUT(Reservoir) r) {
  r.age = min(reservoir_age(r) + 1u, kReservoirMaxAge) | (r.age & ~kReservoirMaxAge);
}

// Guard for a weight about to enter a reservoir: finite, non-negative, bounded.
LANTERN_FUNC float reservoir_weight_guard(float w) {
  return min(finite_positive_or_zero(w), kMaxReservoirWeight);
}

// Core of every update: adds `weight` and keeps `candidate` with probability weight / weight_sum
// (u uniform in [0,1)). Returns true when the candidate was selected. Does not touch M.
LANTERN_FUNC bool reservoir_add(LANTERN_INOUT(Reservoir) r, LightSample candidate, float weight,
                                float u) {
  float w = reservoir_weight_guard(weight);
  r.weight_sum += w;
  bool take = w > 0.0f && u * r.weight_sum < w;
  if (take) {
    r.selected = candidate;
  }
  return take;
}

// Streams one fresh candidate (M += 1). weight = m_i * p̂(y_i) / p_source(y_i); the candidate
// carries p̂(y_i) in target_pdf.
LANTERN_FUNC bool reservoir_update(LANTERN_INOUT(Reservoir) r, LightSample candidate, float weight,
                                   float u) {
  r.M += 1.0f;
  bool take = reservoir_add(r, candidate, weight, u);
  if (take) {
    r.age = 0u;
  }
  return take;
}

// Merges finalized reservoir `other` (from another pixel or frame) into r. target_pdf_here is
// p̂ of other's sample re-evaluated at r's pixel; mis_weight is other's m_i at that sample.
// The weight is m_i * p̂_here(y) * W_other and M accumulates other's confidence.
LANTERN_FUNC bool reservoir_merge(LANTERN_INOUT(Reservoir) r, Reservoir other, float mis_weight,
                                  float target_pdf_here, float u) {
  LightSample moved = other.selected;
  moved.target_pdf = finite_positive_or_zero(target_pdf_here);
  float w =
      finite_positive_or_zero(mis_weight) * moved.target_pdf * finite_positive_or_zero(other.W);
  r.M += finite_positive_or_zero(other.M);
  bool take = reservoir_add(r, moved, w, u);
  if (take) {
    r.age = other.age;
  }
  return take;
}

// Generalized RIS contribution weight: W = weight_sum / p̂(y). Zero when nothing was selected
// or p̂(y) = 0 (the sample then carries no contribution).
LANTERN_FUNC void reservoir_finalize(LANTERN_INOUT(Reservoir) r) {
  r.W = r.selected.light_index == kInvalidLight ? 0.0f
                                                : safe_ratio(r.weight_sum, r.selected.target_pdf);
  if (r.W == 0.0f) {
    r.selected.light_index = kInvalidLight;
  }
}

// Removes the selected sample but keeps the confidence M: the domain "produced nothing" this time
// (a valid outcome, contribution zero). Used for a history sample whose light was removed. M must
// stay: the canonical sample's MIS weight may not depend on whether the other domain's draw
// survived (dropping M there overweights the canonical exactly when the history is empty, a
// positive bias of up to half the empty fraction; tests/shared_math/reservoir_chain_test.cpp).
LANTERN_FUNC void reservoir_drop_sample(LANTERN_INOUT(Reservoir) r) {
  r.selected = light_sample_make(kInvalidLight, vec2(0.0f), 0.0f);
  r.weight_sum = 0.0f;
  r.W = 0.0f;
}

// A history reservoir's light index moved to this frame's light list: `current_index` is the
// remapped index (kInvalidLight: the light was removed). An empty reservoir stays empty and, like
// a removed light's, keeps its M (see reservoir_drop_sample).
LANTERN_FUNC void reservoir_remap_light(LANTERN_INOUT(Reservoir) r, uint current_index) {
  if (r.selected.light_index == kInvalidLight) {
    return;
  }
  if (current_index == kInvalidLight) {
    reservoir_drop_sample(r);
  } else {
    r.selected.light_index = current_index;
  }
}

// Clamps the confidence M (e.g. temporal history to 20x the current M) so old samples cannot
// dominate forever. Only M changes: W stays the sample's contribution weight.
// A non-finite max_m means no cap.
LANTERN_FUNC void reservoir_cap_m(LANTERN_INOUT(Reservoir) r, float max_m) {
  if (is_finite(max_m)) {
    r.M = min(r.M, max(max_m, 0.0f));
  }
}

LANTERN_END_SHARED

#endif
