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

#include "shared/alias_table.h"
#include "shared/environment.h"
#include "shared/light_eval.h"
#include "shared/lights.h"
#include "shared/volume_grid.h"

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
  float u0 = clamp((u_select - p_env) / max(1.0 - p_env, 1e-30), 0.0, 0.99999994);
  uint slot = alias_slot(lights, u0);
  m.index = alias_select(u1, light_alias.e[slot], slot);
  GpuLight light = scene_lights.l[m.index];
  m.pdf = (1.0 - p_env) * light_alias.e[m.index].pdf * light_eval_point_pdf(light);
  m.uv = u_light;
  m.positional = light_kind(light) != kLightDirectional;
  if (m.positional) m.y = light_eval_position(light, u_light, vec3(0.0), fc.scene.x);
  return m.pdf > 0.0;
}

// The unshadowed contribution phase Le G of light `m` at medium point x (camera ray direction
// `dir`, anisotropy g), and the point its shadow ray ends at.
vec3 medium_light_contribution(MediumLight m, vec3 x, vec3 dir, float g, out vec3 target) {
  float far_t = kDirectionalShadowRadii * frame_constants.frame.scene.x;
  if (m.index == kInvalidLight) {
    target = x + m.direction * far_t;
    return light_eval_scattered_incident(m.direction, m.radiance, 1.0, dir, g);
  }
  GpuLight light = scene_lights.l[m.index];
  target = m.positional ? m.y : light_eval_position(light, m.uv, x, frame_constants.frame.scene.x);
  return light_eval_scattered_at(light, target, x, dir, g);
}

// One single-scattering sample of volume `medium` along origin + t dir (dir unit), t in
// [0, t_end]: an unbiased estimate of the radiance it scatters towards the origin.
vec3 volume_inscatter_sample(uint medium, vec3 origin, vec3 dir, float t_end, inout uint rng) {
  GpuVolume v = scene_volumes.v[medium];
  vec3 o = (v.world_to_index * vec4(origin, 1.0)).xyz;
  vec3 d = mat3(v.world_to_index) * dir;
  float t0 = 0.0;
  float t1 = t_end;
  if (!ray_box_clip(v.support_min.xyz, v.support_max.xyz, o, d, t0, t1)) return vec3(0.0);
  MediumLight m;
  if (!medium_choose_light(rng, m)) return vec3(0.0);
  float guide = v.support_min.w * v.absorption.w;  // mean non-zero extinction (max channel)
  float pdf_t;
  float t = scatter_distance_sample(origin, dir, t0, t1, guide, m.positional, m.y,
                                    rng_next_vec2(rng), pdf_t);
  if (!(pdf_t > 0.0)) return vec3(0.0);
  vec3 sigma_s = volume_density_index(v, o + t * d) * v.scattering.xyz;
  if (!(max(sigma_s.x, max(sigma_s.y, sigma_s.z)) > 0.0)) return vec3(0.0);
  vec3 x = origin + t * dir;
  vec3 target;
  vec3 c = medium_light_contribution(m, x, dir, v.scattering.w, target);
  if (c == vec3(0.0)) return vec3(0.0);
  if (!vis_visible(x, target)) return vec3(0.0);
  vec3 transmittance =
      scene_transmittance(origin, dir, t, rng) * scene_transmittance_between(x, target, rng);
  return transmittance * sigma_s * c / (pdf_t * m.pdf);
}

// One sample of every volume's in-scattering along the ray (their sum).
vec3 scene_inscatter_sample(vec3 origin, vec3 dir, float t_end, inout uint rng) {
  vec3 sum = vec3(0.0);
  uint count = frame_constants.frame.media.x;
  for (uint i = 0u; i < count; ++i) sum += volume_inscatter_sample(i, origin, dir, t_end, rng);
  return sum;
}

#endif
