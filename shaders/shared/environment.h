// Environment map: lookup, importance sampling and pdf of an equirectangular (lat-long) radiance
// map, one source for the CPU (lighting/lights/environment_map.h builds the tables; tests run this
// code) and the GPU (shaders/integrators/reference.comp).
//
// Map convention: Blender's world texture (Environment Texture node, equirectangular, default
// mapping), carried into our +Y-up world by the glTF axis conversion (Blender (x, y, z) = our
// (x, -z, y)); docs/levels.md "Environment map convention" (and how pbrt-v4 differs). In map
// space (world space rotated by the level's `rotation_deg`):
//   column u in [0,1) left to right: azimuth phi = 2 pi (u - 1/2), direction
//     (sin(theta) cos(phi), cos(theta), sin(theta) sin(phi)): the image centre (u = 0.5) looks
//     down +X, u = 0.25 is -Z, u = 0.75 is +Z, the left/right edge -X (Blender: centre +X,
//     0.25 +Y, 0.75 -Y; Cycles' direction_to_equirectangular); as u grows the azimuth turns
//     from -Z through +X to +Z (clockwise seen from above, +Y);
//   row v in [0,1) top to bottom: polar angle theta = pi v from +Y (top row = straight up).
// Texels are piecewise constant (nearest; no filtering), so the sampling density below is
// exactly proportional to the luminance of what the lookup returns.
//
// Sampling: pixel (x, y) is drawn with probability p = lum(x, y) dw(y) / sum(lum dw), where
// dw(y) = (2 pi / W)(cos theta0(y) - cos theta1(y)) is its exact solid angle, from two alias
// tables (O(1)): the marginal over rows (p(y), `marginal`, H entries) and the conditional over the
// columns of each row (p(x | y), `conditional`, W entries per row). Inside the pixel, phi is
// uniform and cos(theta) is uniform between the row's bounds, so the solid-angle pdf is constant
// over the pixel: pdf(w) = p(x, y) / dw(y). It integrates to 1 over the sphere.
//
// Memory is reached through three fetch functions, declared here; a GLSL shader defines them
//   vec4 env_fetch_texel(uint i); AliasEntry env_fetch_marginal(uint i);
//   AliasEntry env_fetch_conditional(uint i);
// the C++ ones (below) take an EnvironmentView as first argument.
#ifndef LANTERN_SHARED_ENVIRONMENT_H
#define LANTERN_SHARED_ENVIRONMENT_H

#include "shared/alias_table.h"
#include "shared/common_math.h"
#include "shared/lang.h"

LANTERN_BEGIN_SHARED

struct GpuEnvironment {
  mat4 world_to_map;  // rotation only (inverse of map_to_world)
  mat4 map_to_world;
  uvec4 size;   // x: width; y: height; z: 1 when it can be importance sampled (not black)
  vec4 params;  // x: probability that a light sample picks the environment; y: mean
                // luminance over the sphere (W/(sr m^2)); z: 1 for a level's map, 0 for
                // the black stand-in bound when there is none; w: 0
};
LANTERN_STATIC_SIZE(GpuEnvironment, 2 * 64 + 2 * 16);

LANTERN_END_SHARED

#ifdef __cplusplus
namespace lantern::gpu {
// The CPU's view of the tables (lighting/lights/environment_map.h owns the arrays).
struct EnvironmentView {
  const vec4* texels = nullptr;             // W * H, row-major from the top row; rgb radiance
  const AliasEntry* marginal = nullptr;     // H
  const AliasEntry* conditional = nullptr;  // W * H, one table of W per row
};
inline vec4 env_fetch_texel(const EnvironmentView& env, uint i) {
  return env.texels[i];
}
inline AliasEntry env_fetch_marginal(const EnvironmentView& env, uint i) {
  return env.marginal[i];
}
inline AliasEntry env_fetch_conditional(const EnvironmentView& env, uint i) {
  return env.conditional[i];
}
inline float env_atan2(float y, float x) {
  return std::atan2(y, x);
}
}  // namespace lantern::gpu
#define LANTERN_ENV_PARAM const EnvironmentView &env_view,
#define LANTERN_ENV env_view,
#else
// Prototypes: the including shader defines them (anywhere; only needed when sampling is used).
vec4 env_fetch_texel(uint i);
AliasEntry env_fetch_marginal(uint i);
AliasEntry env_fetch_conditional(uint i);
float env_atan2(float y, float x) {
  return atan(y, x);
}
#define LANTERN_ENV_PARAM
#define LANTERN_ENV
#endif

LANTERN_BEGIN_SHARED

// Map-space direction -> (u, v) in [0,1]^2 (see the convention above).
LANTERN_FUNC vec2 env_direction_to_uv(vec3 d) {
  float u = env_atan2(d.z, d.x) * (0.5f * kInvPi) + 0.5f;
  float v = acos(clamp(d.y, -1.0f, 1.0f)) * kInvPi;
  return vec2(u, v);
}

// Map-space unit direction of azimuth phi = 2 pi (u - 1/2) and polar angle theta (given by its
// cosine and sine): the one place the convention above turns angles into a direction.
LANTERN_FUNC vec3 env_angles_to_direction(float phi, float cos_theta, float sin_theta) {
  return vec3(sin_theta * cos(phi), cos_theta, sin_theta * sin(phi));
}

// (u, v) in [0,1]^2 -> map-space unit direction (inverse of env_direction_to_uv).
LANTERN_FUNC vec3 env_uv_to_direction(vec2 uv) {
  float phi = kTwoPi * uv.x - kPi;
  float theta = kPi * uv.y;
  return env_angles_to_direction(phi, cos(theta), sin(theta));
}

// World-space direction <-> (u, v) of the map (the form ReSTIR stores an environment sample in).
LANTERN_FUNC vec2 env_world_direction_to_uv(GpuEnvironment env, vec3 world_dir) {
  return env_direction_to_uv(normalize(vec3(env.world_to_map * vec4(world_dir, 0.0f))));
}
LANTERN_FUNC vec3 env_uv_to_world_direction(GpuEnvironment env, vec2 uv) {
  return normalize(vec3(env.map_to_world * vec4(env_uv_to_direction(uv), 0.0f)));
}

// Texel index of a world-space direction (clamped to the image).
LANTERN_FUNC uvec2 env_texel_of(GpuEnvironment env, vec3 world_dir) {
  vec3 d = normalize(vec3(env.world_to_map * vec4(world_dir, 0.0f)));
  vec2 uv = env_direction_to_uv(d);
  uint x = min(uint(max(uv.x, 0.0f) * float(env.size.x)), env.size.x - 1u);
  uint y = min(uint(max(uv.y, 0.0f) * float(env.size.y)), env.size.y - 1u);
  return uvec2(x, y);
}

// Solid angle of one texel of row y: (2 pi / W)(cos theta0 - cos theta1).
LANTERN_FUNC float env_texel_solid_angle(GpuEnvironment env, uint y) {
  float theta0 = kPi * float(y) / float(env.size.y);
  float theta1 = kPi * float(y + 1u) / float(env.size.y);
  return (kTwoPi / float(env.size.x)) * max(cos(theta0) - cos(theta1), 0.0f);
}

// Radiance arriving from world-space direction `world_dir` (pointing away from the receiver).
LANTERN_FUNC vec3 env_radiance(LANTERN_ENV_PARAM GpuEnvironment env, vec3 world_dir) {
  uvec2 t = env_texel_of(env, world_dir);
  return vec3(env_fetch_texel(LANTERN_ENV t.y * env.size.x + t.x));
}

// Solid-angle pdf of env_sample producing world_dir (0 when the map cannot be sampled).
LANTERN_FUNC float env_pdf(LANTERN_ENV_PARAM GpuEnvironment env, vec3 world_dir) {
  if (env.size.z == 0u) {
    return 0.0f;
  }
  uvec2 t = env_texel_of(env, world_dir);
  float p = env_fetch_marginal(LANTERN_ENV t.y).pdf *
            env_fetch_conditional(LANTERN_ENV t.y * env.size.x + t.x).pdf;
  return safe_ratio(p, env_texel_solid_angle(env, t.y));
}

// Draws a world-space direction from u in [0,1)^4; returns its solid-angle pdf (0: no sample) and
// the radiance arriving from it. u.x/u.y pick the row (slot, alias), u.z/u.w the column; the
// fractional parts of the slot positions place the point inside the texel.
LANTERN_FUNC float env_sample(LANTERN_ENV_PARAM GpuEnvironment env, vec4 u,
                              LANTERN_OUT(vec3) world_dir, LANTERN_OUT(vec3) radiance) {
  world_dir = vec3(0.0f, 1.0f, 0.0f);
  radiance = vec3(0.0f);
  if (env.size.z == 0u) {
    return 0.0f;
  }
  uint w = env.size.x;
  uint h = env.size.y;
  float sy = u.x * float(h);
  uint slot_y = min(uint(sy), h - 1u);
  uint y = alias_select(u.y, env_fetch_marginal(LANTERN_ENV slot_y), slot_y);
  float sx = u.z * float(w);
  uint slot_x = min(uint(sx), w - 1u);
  uint x = alias_select(u.w, env_fetch_conditional(LANTERN_ENV y * w + slot_x), slot_x);
  float jx = clamp(sx - float(slot_x), 0.0f, 1.0f);
  float jy = clamp(sy - float(slot_y), 0.0f, 1.0f);
  float p =
      env_fetch_marginal(LANTERN_ENV y).pdf * env_fetch_conditional(LANTERN_ENV y * w + x).pdf;
  // phi uniform over the column, cos(theta) uniform between the row's bounds.
  float phi = kTwoPi * ((float(x) + jx) / float(w)) - kPi;
  float c0 = cos(kPi * float(y) / float(h));
  float c1 = cos(kPi * float(y + 1u) / float(h));
  float cos_theta = clamp(mix(c0, c1, jy), -1.0f, 1.0f);
  float sin_theta = sqrt(max(1.0f - cos_theta * cos_theta, 0.0f));
  vec3 d = env_angles_to_direction(phi, cos_theta, sin_theta);
  world_dir = normalize(vec3(env.map_to_world * vec4(d, 0.0f)));
  radiance = vec3(env_fetch_texel(LANTERN_ENV y * w + x));
  return safe_ratio(p, env_texel_solid_angle(env, y));
}

LANTERN_END_SHARED

#undef LANTERN_ENV_PARAM
#undef LANTERN_ENV

#endif  // LANTERN_SHARED_ENVIRONMENT_H
