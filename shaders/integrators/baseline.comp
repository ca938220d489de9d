// integrators.baseline: direct lighting with one light sample per pixel. The primary hit comes
// from the G-buffer (position, facing normals, material id, emission seen from the camera); one
// light sample: the environment map with probability env.params.x (its luminance x solid-angle
// distribution, shared/environment.h), else one emitter from the power alias table, evaluated by
// shared/light_eval.h (the light evaluation of ReSTIR and the reference); one shadow ray. Sky
// pixels show the environment along the camera ray (lib/environment.glsl env_sky_radiance; the
// uniform sky colour without a map).
// Reads: G-buffer images (shared/gbuffer.h) and the scene (lib/scene_buffers.glsl: materials,
// lights, alias table, environment, BVH through lib/visibility.glsl, frame constants).
// Writes: radiance (rgba32f per pixel, row-major from the top-left; the host averages
// frames). History: none.
// Host visibility (shared/host_visibility.h): the "hostemit" variant (integrators.baseline) shades
// as if every ray got through and writes the rays; after visibility.host, the "hostresolve"
// variant (integrators.baseline_occluded) rewrites the pixels whose ray was blocked.
// Dispatch: a 1D grid of tiles (lib/pixel_groups.glsl's shape), shuffled (push.tile_stride,
// pixel_tile_origin): lavapipe hands each CPU thread a contiguous range of workgroups, so
// without the shuffle the thread that gets the sky idles while the other traces the geometry
// (shared/PLATFORM.md, 1.45-1.6x on ray casting).
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lib/pixel_groups.glsl"
#include "lib/scene_buffers.glsl"
#include "integrators/baseline.h"
#include "shared/alias_table.h"
#include "shared/brdf.h"
#include "shared/color.h"
#include "shared/common_math.h"
#include "shared/gbuffer.h"
#include "shared/light_eval.h"
#include "shared/lights.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/scene.h"
#include "shared/textures.h"

layout(std430, binding = PASS_BINDING(0)) writeonly buffer RadianceBuffer {
  vec4 pixels[];
} radiance;
layout(binding = PASS_BINDING(1), rgba32f) uniform readonly image2D gbuffer_position;
layout(binding = PASS_BINDING(2), rgba32f) uniform readonly image2D gbuffer_normal;
layout(binding = PASS_BINDING(3), rgba32f) uniform readonly image2D gbuffer_emission_metallic;
layout(binding = PASS_BINDING(4), rgba32ui) uniform readonly uimage2D gbuffer_ids;
layout(binding = PASS_BINDING(5), rgba16f) uniform readonly image2D gbuffer_albedo_roughness;

layout(push_constant) uniform Push { BaselinePush push; };

// One light sample: returns the estimate c V T / p towards light `index`, drawn with probability
// select_pdf (c, p: shared/light_eval.h, the same evaluation as ReSTIR and the reference; T the
// media's transmittance along the shadow ray, lib/volumes.glsl).
vec3 sample_light(uint index, float select_pdf, vec3 x, vec3 n, vec3 ng, vec3 v, GpuMaterial mat,
                  vec2 u, inout uint rng) {
  GpuLight light = scene_light(index);
  float pdf = select_pdf * light_eval_point_pdf(light);
  if (!(pdf > 0.0)) return vec3(0.0);
  vec3 y = light_eval_position(light, u, x, frame_constants.frame.scene.x);
  vec3 c = light_eval_contribution_at(light, y, x, n, ng, v, mat.base_color.rgb, mat.params.x,
                                      mat.params.y, mat.params.z);
  if (c == vec3(0.0)) return vec3(0.0);
  if (!vis_visible(x, y)) return vec3(0.0);
  return c * scene_transmittance_between(x, y, rng) / pdf;
}

// One environment sample (drawn with probability p_env): f * L * cos / pdf, visibility included.
vec3 sample_environment(float p_env, vec3 x, vec3 n, vec3 ng, vec3 v, GpuMaterial mat, vec4 u,
                        inout uint rng) {
  vec3 l;
  vec3 le;
  float pdf = p_env * env_sample(env_header.env, u, l, le);
  if (!(pdf > 0.0)) return vec3(0.0);
  vec3 c = light_eval_incident(l, le, 1.0, n, ng, v, mat.base_color.rgb, mat.params.x,
                               mat.params.y, mat.params.z);
  if (c == vec3(0.0)) return vec3(0.0);
  float far_t = kDirectionalShadowRadii * frame_constants.frame.scene.x;
  if (!vis_visible(x, x + l * far_t)) return vec3(0.0);
  return c * scene_transmittance(x, l, far_t, rng) / pdf;
}

vec3 shade_pixel(uvec2 pixel) {
  FrameConstants fc = frame_constants.frame;
  ivec2 p = ivec2(pixel);
  vec4 position = imageLoad(gbuffer_position, p);
  if (gbuffer_is_sky(position.w)) return env_sky_radiance(fc, pixel);
  vec4 normals = imageLoad(gbuffer_normal, p);
  uvec4 ids = imageLoad(gbuffer_ids, p);
  vec4 emission_metallic = imageLoad(gbuffer_emission_metallic, p);
  GpuMaterial mat = material_at_gbuffer(scene_materials.m[ids.y],
                                        imageLoad(gbuffer_albedo_roughness, p),
                                        emission_metallic.w);
  vec3 x = position.xyz;
  vec3 v = normalize(fc.camera_position.xyz - x);
  vec3 n = oct_decode(normals.xy);   // shading normal, facing the camera
  vec3 ng = oct_decode(normals.zw);  // geometric normal, facing the camera
  if (dot(n, ng) < 0.0) n = -n;
  vec3 result = emission_metallic.rgb;
  float p_env = env_header.env.params.x;  // 0 without a map; 1 when no emitter has power
  if (frame_constants.frame.counts.x > 0u || p_env > 0.0) {
    uint rng = frame_rng(pixel, kBaselineRngPass);
    float u_select = rng_next_float(rng);
    float u1 = rng_next_float(rng);
    vec2 u_light = rng_next_vec2(rng);
    if (u_select < p_env) {
      result +=
          sample_environment(p_env, x, n, ng, v, mat, vec4(u_light, u1, rng_next_float(rng)), rng);
    } else if (frame_constants.frame.counts.x > 0u) {
      // Reuse u_select, rescaled to [0,1), for the alias slot.
      uint index = scene_light_sample(scene_light_draw_u0(u_select, p_env), u1);
      float select_pdf = scene_light_strategy_pdf(index, p_env);
      result += sample_light(index, select_pdf, x, n, ng, v, mat, u_light, rng);
    }
  }
  return result;
}

// Never write NaN/Inf: a non-finite sample counts as black.
void write_radiance(uint index, vec3 value) {
  if (!(is_finite(value.x) && is_finite(value.y) && is_finite(value.z))) value = vec3(0.0);
  radiance.pixels[index] = vec4(max(value, vec3(0.0)), 1.0);
}

void main() {
  uvec2 size = frame_constants.frame.frame.xy;
  uvec2 pixel =
      pixel_tile_origin(gl_WorkGroupID.x, push.tile_stride, 0u, size, gl_WorkGroupSize.xy) +
      gl_LocalInvocationID.xy;
  if (pixel.x >= size.x || pixel.y >= size.y) return;
  uint index = pixel.y * size.x + pixel.x;
#ifdef LANTERN_VISIBILITY_HOST_RESOLVE
  // After visibility.host: a pixel whose ray was blocked shows its emission only (what the light
  // sample adds is zero); the others keep the emit variant's value.
  HostShadowRay ray = host_rays.r[index];
  if (host_ray_traced(ray) && !host_ray_visible(ray)) {
    write_radiance(index, imageLoad(gbuffer_emission_metallic, ivec2(pixel)).rgb);
  }
#else
  vis_host_begin(index);
  write_radiance(index, shade_pixel(pixel));
#endif
}
