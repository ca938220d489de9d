// The media reservoirs of volume.restir_* (shared/volume_restir.h) in registers: load, store
// (guarded: no NaN, Inf or negative weight reaches a buffer) and the weighted reservoir sampling
// step. Needs lib/volume_scatter.glsl first.
#ifndef LANTERN_LIB_VOLUME_RESERVOIR_GLSL
#define LANTERN_LIB_VOLUME_RESERVOIR_GLSL

#include "shared/volume_restir.h"

struct MediaReservoir {
  VolumeSample y;
  float W;       // contribution weight
  float M;       // confidence
  float target;  // p̂(y) at the owning pixel
  vec3 dir;      // the owning pixel's camera ray
  float t_end;
};

MediaReservoir media_reservoir_empty(vec3 dir, float t_end) {
  MediaReservoir r;
  r.y.medium = 0u;
  r.y.t = 0.0;
  r.y.light = kInvalidLight;
  r.y.uv = vec2(0.0);
  r.W = 0.0;
  r.M = 0.0;
  r.target = 0.0;
  r.dir = dir;
  r.t_end = t_end;
  return r;
}

MediaReservoir media_reservoir_load(VolumeReservoir v) {
  MediaReservoir r;
  r.y.t = v.scatter.x;
  r.y.uv = v.scatter.yz;
  r.y.light = v.light;
  r.y.medium = v.medium;
  r.W = v.scatter.w;
  r.M = v.M;
  r.target = v.target;
  r.dir = v.ray.xyz;
  r.t_end = v.ray.w;
  return r;
}

// An empty reservoir keeps its confidence M: the balance heuristic counts the candidates it
// drew even when none survived.
VolumeReservoir media_reservoir_store(MediaReservoir r) {
  bool ok = r.y.light != kInvalidLight && is_finite(r.W) && r.W > 0.0 && is_finite(r.target) &&
            r.target > 0.0 && is_finite(r.y.t);
  VolumeReservoir v;
  v.scatter = vec4(ok ? r.y.t : 0.0, ok ? r.y.uv : vec2(0.0),
                   ok ? min(r.W, kMaxReservoirWeight) : 0.0);
  v.ray = vec4(r.dir, r.t_end);
  v.M = finite_positive_or_zero(r.M);
  v.target = ok ? r.target : 0.0;
  v.light = ok ? r.y.light : kInvalidLight;
  v.medium = ok ? r.y.medium : 0u;
  return v;
}

// One step of weighted reservoir sampling: adds w (guarded) to w_sum; true when the new
// candidate replaces the kept one.
bool media_reservoir_take(inout float w_sum, float w, inout uint rng) {
  w = finite_positive_or_zero(w);
  if (!(w > 0.0)) return false;
  w_sum += w;
  return rng_next_float(rng) * w_sum < w;
}

#endif
