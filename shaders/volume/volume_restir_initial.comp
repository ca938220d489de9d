// volume.restir_initial: each pixel's media reservoir for this frame (shared/volume_restir.h).
// Initial: push.candidates (medium, distance, light) candidates drawn along the pixel's camera
// ray (a medium uniformly, then lib/volume_scatter.glsl volume_sample_draw), resampled by the
// target p̂ (RIS). Temporal: a point of the ray chosen without its samples (history_point,
// carried back by its medium's motion) is projected into last frame's camera; the reservoir
// there (its light remapped to this frame's index, its confidence capped at push.m_cap) is
// shifted onto this frame's ray at the point nearest where its medium carried it
// (shared/volume_restir.h volume_temporal_shift, Jacobian a) and
// combined with this frame's by the balance heuristic over the two pixels' targets (both
// evaluated in this frame's scene on each pixel's own ray, the Jacobian applied), so the
// combination stays unbiased where the media and lights hold still.
// Reads: gbuffer position; last frame's final media reservoirs ("reservoirs_history"; without
// history a stand-in that is not read); the scene (volumes, lights, environment).
// Writes: "reservoirs" (one VolumeReservoir per pixel). Dispatch: one thread per pixel, 8x8.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lib/scene_buffers.glsl"
#include "lib/volume_scatter.glsl"
#include "lib/volume_reservoir.glsl"

layout(local_size_x = kVolumeGroupSize, local_size_y = kVolumeGroupSize) in;

layout(std430, binding = PASS_BINDING(0)) restrict writeonly buffer Out {
  VolumeReservoir r[];
} reservoirs;
layout(std430, binding = PASS_BINDING(1)) restrict readonly buffer History {
  VolumeReservoir r[];
} reservoirs_history;
layout(binding = PASS_BINDING(2), rgba32f) uniform readonly image2D gbuffer_position;

layout(push_constant) uniform Push { VolumeRestirPush push; };

// RIS over push.candidates candidates of the ray.
MediaReservoir initial_reservoir(vec3 origin, vec3 dir, float t_end, inout uint rng) {
  MediaReservoir r = media_reservoir_empty(dir, t_end);
  uint media = frame_constants.frame.media.x;
  uint candidates = clamp(push.candidates, 1u, kVolumeRestirMaxCandidates);
  float w_sum = 0.0;
  for (uint k = 0u; k < candidates; ++k) {
    uint medium = min(uint(rng_next_float(rng) * float(media)), media - 1u);
    float pdf;
    VolumeSample s = volume_sample_draw(medium, origin, dir, t_end, rng, pdf);
    pdf /= float(media);
    if (!(pdf > 0.0)) continue;
    float target = volume_sample_target(s, origin, dir, t_end);
    if (media_reservoir_take(w_sum, target / pdf, rng)) {
      r.y = s;
      r.target = target;
    }
  }
  r.M = float(candidates);
  r.W = r.target > 0.0 ? w_sum / (r.M * r.target) : 0.0;
  if (!(r.target > 0.0)) r.y.light = kInvalidLight;
  return r;
}

// Where a pixel looks for history: a point of its ray chosen without its samples (pairing by
// the selected sample, or skipping pixels whose candidates found nothing, would make the reuse
// depend on the outcome it combines: a bias under camera motion), one mean free path (at the
// guide extinction) into the nearest volume the ray crosses, at most halfway through it, carried
// back by that medium's motion to where it was last frame; where the ray ends (the surface, or a
// sky pixel's far point) when it crosses none.
vec3 history_point(vec3 origin, vec3 dir, float t_end) {
  float nearest = t_end;
  float point = t_end;
  uint medium = kInvalidLight;
  uint media = frame_constants.frame.media.x;
  for (uint i = 0u; i < media; ++i) {
    GpuVolume v;
    vec3 o, d;
    float t0, t1;
    if (!volume_ray_segment(i, origin, dir, t_end, v, o, d, t0, t1) || !(t0 < nearest)) continue;
    float half_way = 0.5 * (t1 - t0);
    float guide = volume_guide_extinction(v);
    nearest = t0;
    point = t0 + (guide > 0.0 ? min(half_way, 1.0 / guide) : half_way);
    medium = i;
  }
  vec3 x = origin + point * dir;
  if (medium == kInvalidLight) return x;
  return vec3(scene_volumes.v[medium].motion_inverse * vec4(x, 1.0));
}

// The temporal shift of a sample of `medium` from last frame's ray (prev_origin, prev_dir) to
// this frame's (shared/volume_restir.h), its motion applied; a = 0 (no shift) for a medium that
// no longer exists.
vec2 media_shift(uint medium, vec3 prev_origin, vec3 prev_dir, vec3 origin, vec3 dir) {
  if (medium >= frame_constants.frame.media.x) return vec2(0.0);
  return volume_temporal_shift(scene_volumes.v[medium].motion, prev_origin, prev_dir, origin,
                               dir);
}

// Last frame's reservoir at the pixel `point` projects to (light remapped, M capped); false
// outside last frame's image or without confidence.
bool history_at(vec3 point, out MediaReservoir h) {
  FrameConstants fc = frame_constants.frame;
  h = media_reservoir_empty(vec3(0.0, 0.0, -1.0), 0.0);
  vec4 clip = fc.prev_view_proj * vec4(point, 1.0);
  if (!(clip.w > 0.0)) return false;
  vec2 q = (clip.xy / clip.w * 0.5 + 0.5) * vec2(push.width, push.height);
  if (!(q.x >= 0.0 && q.y >= 0.0 && q.x < float(push.width) && q.y < float(push.height))) {
    return false;
  }
  uvec2 qp = uvec2(q);
  h = media_reservoir_load(reservoirs_history.r[qp.y * push.width + qp.x]);
  uint light = h.y.light;
  if (light != kInvalidLight && light != kEnvironmentLight) {
    light = scene_light_from_previous(light);
  }
  h.y.light = light;
  h.M = min(h.M, push.m_cap);
  return h.M > 0.0;  // an empty one still counts: its candidates share the balance heuristic
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= push.width || pixel.y >= push.height) return;
  FrameConstants fc = frame_constants.frame;
  vec3 camera = fc.camera_position.xyz;
  vec4 position = imageLoad(gbuffer_position, ivec2(pixel));
  vec3 dir;
  float t_end;
  media_camera_ray(fc, pixel, position, dir, t_end);
  uint rng = frame_rng(pixel, kVolumeRngRestirInitial);
  MediaReservoir r = initial_reservoir(camera, dir, t_end, rng);

  MediaReservoir h;
  vec3 prev_camera = fc.prev_camera_position.xyz;
  bool reuse = (push.flags & kVolumeRestirFlagHistoryValid) != 0u &&
               history_at(history_point(camera, dir, t_end), h);
  if (reuse) {
    // Balance heuristic with confidence weights over {this frame, history}, in this frame's
    // measure: the history's target of a sample y of medium m here is p̂_h(shift_m^-1 y) / a_m
    // (0 where medium m has no shift); the history's sample contributes through its own
    // medium's shift, its Jacobian applied.
    vec2 shift_c = media_shift(r.y.medium, prev_camera, h.dir, camera, dir);
    vec2 shift_h = media_shift(h.y.medium, prev_camera, h.dir, camera, dir);
    float a_c = shift_c.x >= kVolumeShiftMinCos ? shift_c.x : 0.0;
    float a_h = shift_h.x >= kVolumeShiftMinCos ? shift_h.x : 0.0;
    VolumeSample back = r.y;
    back.t = a_c > 0.0 ? volume_shift_back(shift_c, r.y.t) : -1.0;
    VolumeSample moved = h.y;
    moved.t = a_h > 0.0 ? volume_shift_forward(shift_h, h.y.t) : -1.0;
    float p_c_of_c = r.target;
    float p_h_of_c =
        r.target > 0.0 ? volume_sample_target(back, prev_camera, h.dir, h.t_end) : 0.0;
    float p_c_of_h = volume_sample_target(moved, camera, dir, t_end);
    float p_h_of_h = volume_sample_target(h.y, prev_camera, h.dir, h.t_end);
    float m_c = 0.0;  // 1 where the history cannot reach this sample (no shift)
    if (p_c_of_c > 0.0) {
      m_c = a_c > 0.0 ? a_c * r.M * p_c_of_c / (a_c * r.M * p_c_of_c + h.M * p_h_of_c) : 1.0;
    }
    float m_h =
        p_h_of_h > 0.0 ? h.M * p_h_of_h / (a_h * r.M * p_c_of_h + h.M * p_h_of_h) : 0.0;
    float w_sum = 0.0;
    media_reservoir_take(w_sum, m_c * p_c_of_c * r.W, rng);
    if (media_reservoir_take(w_sum, m_h * p_c_of_h * h.W * a_h, rng)) {
      r.y = moved;
      r.target = p_c_of_h;
    }
    r.M += h.M;
    r.W = r.target > 0.0 ? w_sum / r.target : 0.0;
  }
  r.dir = dir;
  r.t_end = t_end;
  reservoirs.r[pixel.y * push.width + pixel.x] = media_reservoir_store(r);
}
