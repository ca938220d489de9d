// The scene's environment map for any pass (baseline, reference, ReSTIR): declares the four
// scene buffers SceneHandles binds by name (env_header, env_texels, env_marginal, env_conditional;
// lighting/scene/scene_buffers.h; included through lib/scene_buffers.glsl), defines the fetches
// shared/environment.h needs, and adds
//   vec3 env_camera_ray_dir(FrameConstants fc, uvec2 pixel)
//     World direction of the camera ray through the centre of `pixel` (row 0 at the top).
//   vec3 env_sky_radiance(FrameConstants fc, uvec2 pixel)
//     What a sky pixel (G-buffer position.w == 0) shows: the environment's radiance along that
//     ray, or fc.environment.rgb (the uniform sky colour) when the level has no map.
//   vec3 env_miss_radiance(vec3 world_dir)
//     Radiance a ray escaping the scene in world_dir receives (black without a map).
// Light selection: env_header.env.params.x is the probability that a light sample picks the
// environment (else the power alias table, scaled by 1 - params.x); env_sample / env_pdf
// (shared/environment.h) draw and evaluate a direction.
// Bindings: set ENV_DESCRIPTOR_SET (default 0), bindings ENV_BINDING_BASE .. + 3 (header,
// texels, marginal, conditional): lib/scene_buffers.glsl sets the base to kSceneEnvHeader, the
// slots of shared/scene_bindings.h. Include it through lib/scene_buffers.glsl.
#ifndef LANTERN_LIB_ENVIRONMENT_GLSL
#define LANTERN_LIB_ENVIRONMENT_GLSL

#include "shared/alias_table.h"
#include "shared/environment.h"
#include "shared/scene.h"

#ifndef ENV_DESCRIPTOR_SET
#define ENV_DESCRIPTOR_SET 0
#endif
#ifndef ENV_BINDING_BASE
#error "lib/environment.glsl: include lib/scene_buffers.glsl (it places the environment's slots)"
#endif

layout(std430, set = ENV_DESCRIPTOR_SET, binding = ENV_BINDING_BASE) readonly buffer
    EnvHeaderBuffer {
  GpuEnvironment env;
} env_header;
layout(std430, set = ENV_DESCRIPTOR_SET, binding = ENV_BINDING_BASE + 1) readonly buffer
    EnvTexelBuffer {
  vec4 t[];
} env_texels;
layout(std430, set = ENV_DESCRIPTOR_SET, binding = ENV_BINDING_BASE + 2) readonly buffer
    EnvMarginalBuffer {
  AliasEntry e[];
} env_marginal;
layout(std430, set = ENV_DESCRIPTOR_SET, binding = ENV_BINDING_BASE + 3) readonly buffer
    EnvConditionalBuffer {
  AliasEntry e[];
} env_conditional;

vec4 env_fetch_texel(uint i) { return env_texels.t[i]; }
AliasEntry env_fetch_marginal(uint i) { return env_marginal.e[i]; }
AliasEntry env_fetch_conditional(uint i) { return env_conditional.e[i]; }

vec3 env_camera_ray_dir(FrameConstants fc, uvec2 pixel) {
  vec2 ndc = (vec2(pixel) + 0.5) / vec2(fc.frame.xy) * 2.0 - 1.0;
  vec4 near_point = fc.inv_view_proj * vec4(ndc, 0.0, 1.0);
  vec4 far_point = fc.inv_view_proj * vec4(ndc, 0.5, 1.0);
  return normalize(far_point.xyz / far_point.w - near_point.xyz / near_point.w);
}

vec3 env_miss_radiance(vec3 world_dir) {
  if (env_header.env.params.z == 0.0) return vec3(0.0);
  return env_radiance(env_header.env, world_dir);
}

vec3 env_sky_radiance(FrameConstants fc, uvec2 pixel) {
  if (env_header.env.params.z == 0.0) return fc.environment.rgb;
  return env_radiance(env_header.env, env_camera_ray_dir(fc, pixel));
}

#endif
