// Shared GLSL of the restir.* passes: push constants, the light list, the tile -> pixel
// mapping, decoding a RestirSurface into a shading point, and the target function p̂ evaluated
// from that decoded point. Every pass evaluates p̂ through restir_contribution() on a packed
// surface, so all domains use exactly the same target function (needed for unbiased MIS).
// The scene (frame constants, lights, environment, BVH) comes from lib/scene_buffers.glsl; a pass
// declares its own resources from PASS_BINDING(0) on. A sample's light index is a light of the
// list or kEnvironmentLight (a direction of the environment map, solid-angle measure;
// shared/reservoir.h).
#ifndef LANTERN_RESTIR_COMMON_GLSL
#define LANTERN_RESTIR_COMMON_GLSL

#include "shared/color.h"
#include "shared/common_math.h"
#include "shared/light_eval.h"
#include "shared/lights.h"
#include "shared/reservoir.h"
#include "shared/reservoir_mis.h"
#include "shared/reservoir_pack.h"
#include "shared/restir.h"
#include "shared/rng.h"
#include "shared/scene.h"

#include "lib/pixel_groups.glsl"
#include "lib/scene_buffers.glsl"
#include "lib/texel_records.glsl"

layout(push_constant) uniform Push { RestirPush push; };

// The frame's facts (FrameConstants, one owner): render size, lights in the alias table, scene
// radius (directional and environment shadow rays).
uvec2 restir_size() { return frame_constants.frame.frame.xy; }
uint restir_light_count() { return frame_constants.frame.counts.x; }
float restir_scene_radius() { return frame_constants.frame.scene.x; }

// The reservoir grid: one reservoir per push.reservoir_stride x push.reservoir_stride pixels
// (restir.initial, restir.temporal and restir.spatial run over its cells; restir.shade over the
// pixels). Each cell resamples for one representative pixel of its block, which moves every frame.
uint restir_stride() { return max(push.reservoir_stride, 1u); }
uvec2 restir_grid_size() { return restir_grid_extent(restir_size(), push.reservoir_stride); }
uvec2 restir_representative(uvec2 cell) {
  uvec2 offset = uvec2(push.representative & 0xffffu, push.representative >> 16u);
  return min(cell * restir_stride() + offset, restir_size() - 1u);
}

// Position of this invocation among tiles of the workgroup's shape (pixel_tile_origin's order)
// over an image of `size`; false outside it.
bool restir_invocation(uvec2 size, out uvec2 position) {
  position = pixel_tile_origin(gl_WorkGroupID.x, push.tile_stride, push.tile_bands, size,
                               gl_WorkGroupSize.xy) +
             gl_LocalInvocationID.xy;
  return position.x < size.x && position.y < size.y;
}
// Pixel of this invocation (restir.shade); false outside the image.
bool restir_pixel(out uvec2 pixel) { return restir_invocation(restir_size(), pixel); }
// Reservoir cell of this invocation (the grid passes); false outside the grid.
bool restir_cell(out uvec2 cell) { return restir_invocation(restir_grid_size(), cell); }

// Index of a cell in the grid's buffers (reservoirs, cell surfaces, temporal status).
uint restir_index(uvec2 cell) { return cell.y * restir_grid_size().x + cell.x; }
// Index of a pixel in the image's buffers (pixel surfaces, hdr, host rays).
uint restir_pixel_index(uvec2 pixel) { return pixel.y * restir_size().x + pixel.x; }

// One neighbour cell drawn uniformly in a disk of push.radius cells around `centre` (two rng
// draws, always taken, so the sequence does not depend on where the draw lands). False when it
// lands on `skip` or outside the grid; otherwise `index` is its cell index.
bool restir_disk_neighbour(ivec2 centre, ivec2 skip, inout uint rng, out uint index) {
  vec2 u = rng_next_vec2(rng);
  float radius = push.radius * sqrt(u.x);
  float angle = kTwoPi * u.y;
  ivec2 q = centre + ivec2(round(radius * vec2(cos(angle), sin(angle))));
  index = 0u;
  if (q == skip || any(lessThan(q, ivec2(0))) ||
      any(greaterThanEqual(q, ivec2(restir_grid_size())))) {
    return false;
  }
  index = restir_index(uvec2(q));
  return true;
}

// A surface decoded once for many p̂ evaluations.
struct ShadingPoint {
  vec3 x;
  vec3 n;
  vec3 ng;
  vec3 v;
  vec3 albedo;
  float roughness;
  float metallic;
  float specular;
  bool valid;
};

ShadingPoint restir_shading_point(RestirSurface s, vec3 camera) {
  ShadingPoint p;
  p.valid = restir_surface_valid(s);
  p.x = restir_surface_position(s);
  p.n = restir_surface_normal(s);
  p.ng = restir_surface_geometric_normal(s);
  vec3 to_camera = camera - p.x;
  p.v = dot(to_camera, to_camera) > 0.0 ? normalize(to_camera) : p.n;
  p.albedo = restir_surface_albedo(s);
  p.roughness = restir_surface_roughness(s);
  p.metallic = restir_surface_metallic(s);
  p.specular = restir_surface_specular(s);
  return p;
}

// Probability that a light-strategy candidate is the environment map (0 without one).
float restir_env_probability() { return env_header.env.params.x; }

// The uv a shader will see after the reservoir is stored: evaluating there keeps p̂ and W exact.
vec2 restir_stored_uv(vec2 uv) { return unpackUnorm2x16(packUnorm2x16(uv)); }

// Where a light-strategy draw u0 in [0,1) goes: true for the environment (its share p_env, or
// every draw when there is no light), u0 then rescaled to [0,1) as the map row's coordinate;
// false for a light, u0 rescaled to [0,1) for the light draw.
bool restir_strategy_environment(inout float u0, float p_env, uint light_count) {
  if (u0 < p_env || light_count == 0u) {
    u0 = clamp(u0 / max(p_env, 1e-30), 0.0, 0.99999994);
    return true;
  }
  u0 = scene_light_draw_u0(u0, p_env);
  return false;
}

// Light strategy density of (light, uv): selection pdf * point density (the alias table's pdf
// is over the emitters; the environment takes p_env of the selections first). Presampled
// candidates have the same marginal density (restir.presample stores it).
float restir_light_strategy_pdf(uint index, float p_env) {
  return scene_light_strategy_pdf(index, p_env) * light_eval_point_pdf(scene_light(index));
}

// Light strategy density of environment direction l (solid angle).
float restir_env_strategy_pdf(vec3 l, float p_env) {
  return p_env > 0.0 ? p_env * env_pdf(env_header.env, l) : 0.0;
}

// Unshadowed contribution of the environment direction stored as map coordinate uv:
// f(v, l) cos(n, l) Le(l) (solid-angle measure).
vec3 restir_env_contribution(ShadingPoint p, vec2 uv) {
  if (env_header.env.params.z == 0.0) return vec3(0.0);
  vec3 l = env_uv_to_world_direction(env_header.env, uv);
  return light_eval_incident(l, env_radiance(env_header.env, l), 1.0, p.n, p.ng, p.v, p.albedo,
                             p.roughness, p.metallic, p.specular);
}

// Unshadowed contribution at p of point uv of the light whose record is `light`.
vec3 restir_light_contribution(ShadingPoint p, GpuLight light, vec2 uv) {
  if (!p.valid) return vec3(0.0);
  return light_eval_contribution(light, uv, p.x, p.n, p.ng, p.v, p.albedo, p.roughness,
                                 p.metallic, p.specular, restir_scene_radius());
}

// Unshadowed contribution of light sample (light, uv) at p (zero for a light index out of range).
vec3 restir_contribution(ShadingPoint p, uint light, vec2 uv) {
  if (!p.valid) return vec3(0.0);
  if (light == kEnvironmentLight) return restir_env_contribution(p, uv);
  if (light >= restir_light_count()) return vec3(0.0);
  return restir_light_contribution(p, scene_light(light), uv);
}

// The point a shadow ray from p aims at for sample (light, uv): on the light, or far along the
// environment direction (as for a directional light).
vec3 restir_light_position(ShadingPoint p, uint light, vec2 uv) {
  if (light == kEnvironmentLight) {
    return p.x + env_uv_to_world_direction(env_header.env, uv) *
                     (kDirectionalShadowRadii * restir_scene_radius());
  }
  return light_eval_position(scene_light(light), uv, p.x, restir_scene_radius());
}

// Sample s's light record, for evaluating s at several points with one fetch
// (restir_target_with_light); undefined, and unread there, unless s names a scene light.
GpuLight restir_sample_light(LightSample s) {
  GpuLight light;
  if (s.light_index < restir_light_count()) light = scene_light(s.light_index);
  return light;
}

// p̂ of sample s at p, with s's light record already fetched (restir_sample_light(s)).
float restir_target_with_light(ShadingPoint p, LightSample s, GpuLight light) {
  if (!p.valid || s.light_index == kInvalidLight) return 0.0;
  vec2 uv = vec2(s.u, s.v);
  if (s.light_index == kEnvironmentLight) return light_eval_target(restir_env_contribution(p, uv));
  if (s.light_index >= restir_light_count()) return 0.0;
  return light_eval_target(restir_light_contribution(p, light, uv));
}

// p̂ of sample s at p.
float restir_target(ShadingPoint p, LightSample s) {
  return restir_target_with_light(p, s, restir_sample_light(s));
}

#endif
