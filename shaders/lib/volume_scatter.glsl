// Single scattering along a camera ray: the light the media scatter into it, from every light
// kind (emissive triangles, point, spot, directional, the environment), as the volume passes
// estimate it. Per volume the ray crosses, one sample is one light (chosen as baseline chooses:
// the environment with probability env.params.x, else the power alias table) and one distance
// in the ray's segment through the volume's support (shared/volume.h scatter_distance_sample:
// exponential with the volume's guide extinction, MIS'd with equiangular sampling toward the
// light's point when it has one), then
//   sigma_s(x) phase Le G V(x, y) T(x, y) T(camera, x) / (pdf_t pdf_light)
// with both transmittances the unbiased residual ratio tracking estimates of lib/volumes.glsl.
// Light evaluation is shared/light_eval.h's (light_eval_scattered_*): one owner for range, cone
// and falloff with the surfaces' lighting.
// Needs lib/scene_buffers.glsl (scene, lights, alias table, environment, visibility) first.
#ifndef LANTERN_LIB_VOLUME_SCATTER_GLSL
#define LANTERN_LIB_VOLUME_SCATTER_GLSL

#include "lib/emitter_hit.glsl"
#include "shared/alias_table.h"
#include "shared/environment.h"
#include "shared/gbuffer.h"
#include "shared/light_eval.h"
#include "shared/lights.h"
#include "shared/reservoir.h"
#include "shared/volume_grid.h"

// The camera ray of a pixel: from the camera to its G-buffer surface, or along its view
// direction to kDirectionalShadowRadii scene radii for a sky pixel.
void media_camera_ray(FrameConstants fc, uvec2 pixel, vec4 position, out vec3 dir,
                      out float t_end) {
  if (gbuffer_is_sky(position.w)) {
    dir = env_camera_ray_dir(fc, pixel);
    t_end = kDirectionalShadowRadii * fc.scene.x;
  } else {
    vec3 to_surface = position.xyz - fc.camera_position.xyz;
    t_end = length(to_surface);
    dir = t_end > 0.0 ? to_surface / t_end : vec3(0.0, 0.0, -1.0);
  }
}

// A light chosen for a scattering point before its distance is drawn (nothing in the choice
// depends on the point, so equiangular sampling can aim at it).
struct MediumLight {
  uint index;       // scene light index; kInvalidLight: the environment
  float pdf;        // selection x the point's density (environment: x its solid-angle pdf)
  vec2 uv;          // the light sample (light_eval_position's uv)
  vec3 y;           // the point on the light (triangles, point and spot lights)
  vec3 direction;   // environment: the sampled direction (to the light)
  vec3 radiance;    // environment: the radiance arriving from it
  bool positional;  // y is a point (not a direction): the equiangular technique applies
};

// False when the scene has nothing to sample (no emitter, no environment power).
bool medium_choose_light(inout uint rng, out MediumLight m) {
  m.index = kInvalidLight;
  m.pdf = 0.0;
  m.uv = vec2(0.0);
  m.y = vec3(0.0);
  m.direction = vec3(0.0, 1.0, 0.0);
  m.radiance = vec3(0.0);
  m.positional = false;
  FrameConstants fc = frame_constants.frame;
  float p_env = env_header.env.params.x;  // 0 without a map; 1 when no emitter has power
  uint lights = fc.counts.x;
  if (lights == 0u && !(p_env > 0.0)) return false;
  float u_select = rng_next_float(rng);
  float u1 = rng_next_float(rng);
  vec2 u_light = rng_next_vec2(rng);
  if (u_select < p_env) {
    float pdf = env_sample(env_header.env, vec4(u_light, u1, rng_next_float(rng)), m.direction,
                           m.radiance);
    m.pdf = p_env * pdf;
    return m.pdf > 0.0;
  }
  if (lights == 0u) return false;
  m.index = scene_light_sample(scene_light_draw_u0(u_select, p_env), u1);
  GpuLight light = scene_light(m.index);
  m.pdf = scene_light_strategy_pdf(m.index, p_env) * light_eval_point_pdf(light);
  m.uv = u_light;
  m.positional = light_kind(light) != kLightDirectional;
  if (m.positional) m.y = light_eval_position(light, u_light, vec3(0.0), fc.scene.x);
  return m.pdf > 0.0;
}

// A scattering sample y = (medium, t, light, uv) (shared/volume_restir.h): the point at distance
// t along a camera ray, lit by light sample (light, uv); kEnvironmentLight: uv is the map
// coordinate of the direction; kInvalidLight: no sample.
struct VolumeSample {
  uint medium;
  float t;
  uint light;
  vec2 uv;
};

VolumeSample volume_sample_of(uint medium, float t, MediumLight m) {
  VolumeSample s;
  s.medium = medium;
  s.t = t;
  s.light = m.index == kInvalidLight ? kEnvironmentLight : m.index;
  s.uv = m.index == kInvalidLight ? env_world_direction_to_uv(env_header.env, m.direction) : m.uv;
  return s;
}

// The ray origin + t dir (dir unit, t in [0, t_end]) in volume `medium`: its record, the ray in
// its index space (o, d; t keeps its units) and the part [t0, t1] inside its support. False when
// the ray misses it.
bool volume_ray_segment(uint medium, vec3 origin, vec3 dir, float t_end, out GpuVolume v,
                        out vec3 o, out vec3 d, out float t0, out float t1) {
  v = scene_volumes.v[medium];
  o = (v.world_to_index * vec4(origin, 1.0)).xyz;
  d = mat3(v.world_to_index) * dir;
  t0 = 0.0;
  t1 = t_end;
  return ray_box_clip(v.support_min.xyz, v.support_max.xyz, o, d, t0, t1);
}

// Where sample s lies on the ray ending at t_end: its volume, the ray in that volume's index
// space (o, d) and where the ray enters its support. False past t_end, outside the support, or
// for a medium or light that no longer exists.
bool volume_sample_locate(VolumeSample s, vec3 origin, vec3 dir, float t_end, out GpuVolume v,
                          out vec3 o, out vec3 d, out float t_enter) {
  FrameConstants fc = frame_constants.frame;
  t_enter = 0.0;
  o = vec3(0.0);
  d = dir;
  bool light_ok = s.light == kEnvironmentLight || s.light < fc.counts.x;
  if (!light_ok || s.medium >= fc.media.x || !(s.t <= t_end)) return false;
  float t_exit;
  if (!volume_ray_segment(s.medium, origin, dir, t_end, v, o, d, t_enter, t_exit)) return false;
  return s.t >= t_enter && s.t <= t_exit;
}

// The light of sample s seen from medium point x on a ray of direction dir (anisotropy g):
// phase Le G (unshadowed), and the point its shadow ray ends at.
vec3 volume_sample_light(VolumeSample s, vec3 x, vec3 dir, float g, out vec3 target) {
  FrameConstants fc = frame_constants.frame;
  if (s.light == kEnvironmentLight) {
    vec3 l = env_uv_to_world_direction(env_header.env, s.uv);
    target = x + l * (kDirectionalShadowRadii * fc.scene.x);
    return light_eval_scattered_incident(l, env_miss_radiance(l), 1.0, dir, g);
  }
  GpuLight light = scene_light(s.light);
  target = light_eval_position(light, s.uv, x, fc.scene.x);
  return light_eval_scattered_at(light, target, x, dir, g);
}

// Sample s on the ray: the scattering point x, its shadow ray's end, and f = sigma_s(x) phase
// Le G (unshadowed, no transmittance). False (f = 0) where volume_sample_locate is, or where the
// light does not reach x.
bool volume_sample_eval(VolumeSample s, vec3 origin, vec3 dir, float t_end, out vec3 x,
                        out vec3 target, out vec3 f) {
  x = origin + s.t * dir;
  target = x;
  f = vec3(0.0);
  GpuVolume v;
  vec3 o, d;
  float t_enter;
  if (!volume_sample_locate(s, origin, dir, t_end, v, o, d, t_enter)) return false;
  vec3 sigma_s = volume_density_index(v, o + s.t * d) * v.scattering.xyz;
  if (!(max(sigma_s.x, max(sigma_s.y, sigma_s.z)) > 0.0)) return false;
  f = sigma_s * volume_sample_light(s, x, dir, v.scattering.w, target);
  return f != vec3(0.0);
}

// ReSTIR's target p̂ of sample s on the ray (shared/volume_restir.h), made cheap: the cell's
// majorant extinction stands in for sigma_s (one cell read instead of eight voxels; it bounds
// the density, so p̂ > 0 wherever the integrand is), scaled by the medium's scattering share,
// times luminance(phase Le G) and the cheap transmittance exp(-guide (t - t_enter)).
float volume_sample_target(VolumeSample s, vec3 origin, vec3 dir, float t_end) {
  GpuVolume v;
  vec3 o, d;
  float t_enter;
  if (!volume_sample_locate(s, origin, dir, t_end, v, o, d, t_enter)) return 0.0;
  float majorant = volume_majorant_index(v, o + s.t * d);  // max_density * absorption.w
  if (!(majorant > 0.0)) return 0.0;
  vec3 target;
  vec3 c = volume_sample_light(s, origin + s.t * dir, dir, v.scattering.w, target);
  float scattering_share = luminance(v.scattering.xyz) / max(v.absorption.w, 1e-30);
  return finite_positive_or_zero(luminance(c) * majorant * scattering_share *
                                 exp(-volume_guide_extinction(v) * max(s.t - t_enter, 0.0)));
}

// The unbiased in-scattering integrand of sample s: f V(x, target) T(origin, x) T(x, target)
// (both transmittances residual ratio tracking estimates of every medium), and the camera ray's
// transmittance to t_end, `surface`, when `want_surface` (else 1): T(origin, x) T(x, t_end) when
// s is shaded (one walk over [0, t] serves both: an unbiased estimate of each, and they only
// ever add), else a walk of its own.
vec3 volume_sample_shade(VolumeSample s, vec3 origin, vec3 dir, float t_end, bool want_surface,
                         inout uint rng, out vec3 surface) {
  vec3 x, target, f;
  surface = vec3(1.0);
  if (!volume_sample_eval(s, origin, dir, t_end, x, target, f)) {
    if (want_surface) surface = scene_transmittance(origin, dir, t_end, rng);
    return vec3(0.0);
  }
  vec3 to_x = scene_transmittance(origin, dir, s.t, rng);
  if (want_surface) surface = to_x * scene_transmittance_segment(origin, dir, s.t, t_end, rng);
  if (!vis_visible(x, target)) return vec3(0.0);
  return f * to_x * scene_transmittance_between(x, target, rng);
}

// Draws one candidate of volume `medium` on the ray: a light (medium_choose_light) and a distance
// in the ray's segment through the support (scatter_distance_sample, MIS'd toward the light's
// point). pdf: their joint density in the sample's measure (0: no candidate).
VolumeSample volume_sample_draw(uint medium, vec3 origin, vec3 dir, float t_end, inout uint rng,
                                out float pdf) {
  VolumeSample none;
  none.medium = medium;
  none.t = 0.0;
  none.light = kInvalidLight;
  none.uv = vec2(0.0);
  pdf = 0.0;
  GpuVolume v;
  vec3 o, d;
  float t0, t1;
  if (!volume_ray_segment(medium, origin, dir, t_end, v, o, d, t0, t1)) return none;
  MediumLight m;
  if (!medium_choose_light(rng, m)) return none;
  float pdf_t;
  float t = scatter_distance_sample(origin, dir, t0, t1, volume_guide_extinction(v),
                                    m.positional, m.y, rng_next_vec2(rng), pdf_t);
  pdf = pdf_t * m.pdf;
  return pdf > 0.0 ? volume_sample_of(medium, t, m) : none;
}

// --- Light/phase MIS (the reference) ------------------------------------------------------------
// With phase MIS each volume's in-scattering sample is two, combined by the power heuristic over
// (distance, light point), both densities in solid angle at the scattering point x:
//   light: volume_sample_draw's (a light, then a distance MIS'd toward its point):
//     p_light(l) p(t | light point);
//   phase: a distance from the truncated exponential alone, p_exp(t), then a direction from the
//     HG phase function traced to the emitter (or the environment) it finds: p_exp(t) hg(l).
// Each technique's density is evaluated for every sample the other makes; a delta light (point,
// spot, directional) only light sampling reaches (weight 1).

// Light sampling's density of a scattering sample at distance t in the segment [t0, t1] (guide
// extinction `guide`) lit along l: from triangle light `light`'s point y at squared distance
// dist2, or from the environment (light == kEnvironmentLight; y, dist2 unused). The light's
// selection and point in solid angle at the scattering point, times the distance's density
// (MIS'd toward y for a triangle, volume_sample_draw).
float volume_light_technique_pdf(uint light, vec3 y, float dist2, vec3 l, vec3 origin, vec3 dir,
                                 float t0, float t1, float guide, float t) {
  if (light == kEnvironmentLight) {
    return env_header.env.params.x * env_pdf(env_header.env, l) *
           exponential_pdf_truncated(guide, t1 - t0, t - t0);
  }
  return triangle_light_pdf(light, dist2, l) *
         scatter_distance_pdf(origin, dir, t0, t1, guide, true, y, t);
}

// The power heuristic weight of light-drawn sample s (its light still exists): 1 for a delta
// light, else against the phase technique's density of the same (t, direction).
float volume_light_mis_weight(VolumeSample s, vec3 origin, vec3 dir, float t_end) {
  GpuVolume v;
  vec3 o, d;
  float t0, t1;
  if (!volume_ray_segment(s.medium, origin, dir, t_end, v, o, d, t0, t1)) return 1.0;
  float guide = volume_guide_extinction(v);
  float p_exp = exponential_pdf_truncated(guide, t1 - t0, s.t - t0);
  vec3 x = origin + s.t * dir;
  vec3 y = x;
  float dist2 = 0.0;
  vec3 l;
  if (s.light == kEnvironmentLight) {
    l = env_uv_to_world_direction(env_header.env, s.uv);
  } else {
    GpuLight light = scene_light(s.light);
    if (light_kind(light) != kLightTriangle) return 1.0;
    y = light_eval_position(light, s.uv, x, frame_constants.frame.scene.x);
    vec3 to_light = y - x;
    dist2 = dot(to_light, to_light);
    l = to_light * inversesqrt(max(dist2, 1e-30));
  }
  float p_light =
      volume_light_technique_pdf(s.light, y, dist2, l, origin, dir, t0, t1, guide, s.t);
  return power_heuristic(p_light, p_exp * hg_pdf(dir, l, v.scattering.w));
}

// The phase technique's estimate for volume `medium` on the ray, MIS-weighted (unbiased
// transmittances from `rng`).
vec3 volume_phase_sample(uint medium, vec3 origin, vec3 dir, float t_end, inout uint rng) {
  GpuVolume v;
  vec3 o, d;
  float t0, t1;
  float u_t = rng_next_float(rng);
  vec2 u_dir = rng_next_vec2(rng);
  if (!volume_ray_segment(medium, origin, dir, t_end, v, o, d, t0, t1)) return vec3(0.0);
  float guide = volume_guide_extinction(v);
  float t = clamp(t0 + exponential_sample_truncated(guide, t1 - t0, u_t), t0, t1);
  float p_exp = exponential_pdf_truncated(guide, t1 - t0, t - t0);
  vec3 sigma_s = volume_density_index(v, o + t * d) * v.scattering.xyz;
  if (!(p_exp > 0.0) || !(max(sigma_s.x, max(sigma_s.y, sigma_s.z)) > 0.0)) return vec3(0.0);
  float g = v.scattering.w;
  vec3 l = hg_sample(dir, g, u_dir);
  float p_dir = hg_pdf(dir, l, g);
  if (!(p_dir > 0.0)) return vec3(0.0);
  vec3 x = origin + t * dir;
  vec3 le;
  vec3 end;
  float p_light;
  VisHit hit;
  if (vis_trace_closest(x, l, kVisInfinity, hit)) {
    SurfaceHit h = surface_at(hit);
    le = emitted(h, scene_materials.m[h.material], l);
    if (le == vec3(0.0)) return vec3(0.0);
    vec3 to_hit = h.position - x;
    p_light = h.light != kInvalidLight
                  ? volume_light_technique_pdf(h.light, h.position, dot(to_hit, to_hit), l,
                                               origin, dir, t0, t1, guide, t)
                  : 0.0;
    end = h.position;
  } else {
    if (env_header.env.size.z == 0u) return vec3(0.0);
    le = env_miss_radiance(l);  // as the light technique sees it (volume_sample_light)
    p_light = volume_light_technique_pdf(kEnvironmentLight, x, 0.0, l, origin, dir, t0, t1,
                                         guide, t);
    end = x + l * (kDirectionalShadowRadii * frame_constants.frame.scene.x);
  }
  float p_phase = p_exp * p_dir;
  vec3 c = sigma_s * light_eval_scattered_incident(l, le, 1.0, dir, g) / p_phase;
  if (c == vec3(0.0)) return vec3(0.0);
  c *= scene_transmittance(origin, dir, t, rng) * scene_transmittance_between(x, end, rng);
  return c * power_heuristic(p_phase, p_light);
}

// One sample of every volume's in-scattering along origin + t dir (dir unit), t in [0, t_end]
// (their sum: an unbiased estimate of the radiance the media scatter towards the origin), and
// an unbiased estimate of the ray's transmittance to t_end, `surface` (shared with the first
// volume's sample, volume_sample_shade). With `phase_mis` each volume adds a phase-sampled
// estimate, the two MIS-weighted (above).
vec3 scene_inscatter_sample(vec3 origin, vec3 dir, float t_end, bool phase_mis, inout uint rng,
                            out vec3 surface) {
  vec3 sum = vec3(0.0);
  surface = vec3(1.0);
  uint count = frame_constants.frame.media.x;
  for (uint i = 0u; i < count; ++i) {
    float pdf;
    VolumeSample s = volume_sample_draw(i, origin, dir, t_end, rng, pdf);
    if (!(pdf > 0.0)) s.light = kInvalidLight;  // nothing to shade: only the transmittance
    vec3 t_surface;
    vec3 f = volume_sample_shade(s, origin, dir, t_end, i == 0u, rng, t_surface);
    if (i == 0u) surface = t_surface;
    if (pdf > 0.0) {
      float weight = phase_mis && f != vec3(0.0) ? volume_light_mis_weight(s, origin, dir, t_end)
                                                 : 1.0;
      sum += f * (weight / pdf);
    }
    if (phase_mis) sum += volume_phase_sample(i, origin, dir, t_end, rng);
  }
  return sum;
}

#endif
