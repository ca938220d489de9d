// restir.shade: per pixel, the final reservoir's sample shaded with one visibility ray:
// radiance = G-buffer emission + c(x, y) V(x, y) W (c = BRDF x cos x Le x G, shared/light_eval.h);
// with push.reservoir_stride > 1 a pixel that is not its cell's representative first resamples a
// similar cell's reservoir for itself (resample_for_pixel);
// sky pixels show the environment map along their camera ray (lib/environment.glsl). With a
// debug view (push.debug_view) writes that view instead. Never writes NaN/Inf.
// Reads: restir_surfaces (every pixel's: restir.initial's pixel_surfaces with a stride > 1),
// reservoirs_in (the final reservoirs, per cell), gbuffer emission_metallic and
// motion, temporal_status, frame constants, lights, environment (env_*), BVH.
// Writes: hdr (vec4 per pixel).
// History: none. Dispatch: one workgroup per tile (lib/pixel_groups.glsl's shape), shuffled
// (push.tile_stride).
// Host visibility (shared/host_visibility.h): the "hostemit" variant (restir.shade) shades as if
// every ray got through and writes the rays; after visibility.host, the "hostresolve" variant
// (restir.shade_occluded) rewrites the pixels whose ray was blocked.
#version 460
#extension GL_GOOGLE_include_directive : require

// The scene (BVH through rgba32ui texel views: 1.24x faster restir.shade than storage buffers on
// night_market) comes from lib/scene_buffers.glsl through restir_common.glsl.
#include "restir/restir_common.glsl"

layout(binding = PASS_BINDING(0), rgba32f) readonly uniform image2D gbuffer_emission_metallic;
layout(binding = PASS_BINDING(1), rgba32f) readonly uniform image2D gbuffer_motion;
layout(binding = PASS_BINDING(2)) uniform utextureBuffer restir_surfaces;
layout(std430, binding = PASS_BINDING(3)) buffer ReservoirInOut {
  PackedReservoir r[];
} reservoirs_in;
layout(std430, binding = PASS_BINDING(4)) readonly buffer StatusIn {
  uint status[];
} temporal_status;
layout(std430, binding = PASS_BINDING(5)) writeonly buffer HdrOut { vec4 pixels[]; } hdr;

vec3 hash_colour(uint x) {
  uint h = pcg_hash(x);
  return vec3(float(h & 0xffu), float((h >> 8u) & 0xffu), float((h >> 16u) & 0xffu)) / 255.0;
}

vec3 debug_view(uint view, uvec2 pixel, uint index, Reservoir r, bool surface) {
  if (view == kRestirDebugW) return vec3(r.W / (1.0 + r.W));
  if (view == kRestirDebugM) return vec3(safe_ratio(r.M, push.m_cap));
  if (view == kRestirDebugAge) {
    return vec3(reservoir_has_sample(r) ? float(reservoir_age(r)) / 32.0 : 0.0);
  }
  if (view == kRestirDebugLight) {
    return reservoir_has_sample(r) ? hash_colour(r.selected.light_index) : vec3(0.0);
  }
  if (view == kRestirDebugDisocclusion) {
    if (!surface) return vec3(0.0);
    uint status = temporal_status.status[index];
    if (status == kRestirStatusNoHistory) return vec3(1.0, 0.0, 0.0);
    return status == kRestirStatusReprojected ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 1.0, 0.0);
  }
  if (view == kRestirDebugMotion) {
    vec2 motion = imageLoad(gbuffer_motion, ivec2(pixel)).xy;
    return vec3(0.5 + motion / 16.0, 0.5);
  }
  return vec3(0.0);
}

// Visibility reuse (push.visibility_reuse = N > 0): a sample whose visibility this pixel's
// history tested is shaded with that verdict and no shadow ray, except on every N-th frame
// (staggered over the tiles), when it is tested again. Biased where occluders or the surface
// point moved since the last test (at most N frames ago); exact for a still camera over still
// geometry.
bool reuse_visibility(Reservoir r) {
  if (push.visibility_reuse == 0u || !reservoir_visibility_known(r)) return false;
  // One phase per workgroup tile: lanes of a SIMD batch re-test together (a per-pixel phase left a
  // lane tracing in nearly every batch, and lavapipe's batch then ran the whole traversal).
  uint phase = pcg_hash(gl_WorkGroupID.x) % push.visibility_reuse;
  return (frame_constants.frame.frame.z + phase) % push.visibility_reuse != 0u;
}

// One candidate of the light strategy at p from rng (the alias table, or the environment with its
// selection probability), with its density `pdf` (area measure for a light point, solid angle
// for the environment). False when there is nothing to draw from.
bool own_light_candidate(ShadingPoint p, inout uint rng, out LightSample y, out float pdf) {
  float p_env = restir_env_probability();
  uint light_count = restir_light_count();
  float u0 = rng_next_float(rng);
  float u1 = rng_next_float(rng);
  vec2 uv = restir_stored_uv(rng_next_vec2(rng));
  y = light_sample_make(kInvalidLight, vec2(0.0), 0.0);
  pdf = 0.0;
  if (light_count == 0u && p_env == 0.0) return false;
  if (restir_strategy_environment(u0, p_env, light_count)) {
    vec3 l, le;
    env_sample(env_header.env, vec4(u0, u1, uv), l, le);
    vec2 env_uv = restir_stored_uv(env_world_direction_to_uv(env_header.env, l));
    pdf = restir_env_strategy_pdf(env_uv_to_world_direction(env_header.env, env_uv), p_env);
    y = light_sample_make(kEnvironmentLight, env_uv, 0.0);
    return true;
  }
  uint index = scene_light_sample(u0, u1);
  pdf = restir_light_strategy_pdf(index, p_env);
  y = light_sample_make(index, uv, 0.0);
  return true;
}

// The cell whose representative a pixel that is not one resamples from: its own cell's when the
// two surfaces are similar (restir_surfaces_similar), else the first that is of the adjacent
// cells towards the pixel. False when none is.
bool similar_cell(uvec2 pixel, RestirSurface surface, uvec2 cell, out uvec2 found,
                  out RestirSurface found_surface) {
  ivec2 towards = ivec2(sign(vec2(pixel) - vec2(restir_representative(cell))));
  ivec2 steps[4] = ivec2[4](ivec2(0), ivec2(towards.x, 0), ivec2(0, towards.y), towards);
  float depth = restir_surface_depth(surface);
  for (uint i = 0u; i < 4u; ++i) {
    if (i > 0u && steps[i] == ivec2(0)) continue;
    ivec2 c = ivec2(cell) + steps[i];
    if (any(lessThan(c, ivec2(0))) || any(greaterThanEqual(c, ivec2(restir_grid_size())))) {
      continue;
    }
    found = uvec2(c);
    found_surface =
        restir_surface_fetch(restir_surfaces, restir_pixel_index(restir_representative(found)));
    if (restir_surfaces_similar(surface, depth, found_surface, push.similarity)) return true;
  }
  return false;
}

// With push.reservoir_stride > 1, at a pixel that is not its cell's representative: a similar
// cell's final reservoir r (similar_cell) resampled for this pixel's point p. Generalized RIS
// over two domains, the representative q's (r's sample, confidence c = r.M) and p's own (one
// light-strategy candidate, confidence 1), MIS weights by the balance heuristic over their
// targets: m_q(y) = c p̂_q(y) / (c p̂_q(y) + p̂_p(y)). The own candidate keeps the estimate
// unbiased where p̂_q is zero and p̂_p is not (at a light's reach, past q's horizon). Where no
// cell is similar (an edge, a strip one pixel wide) the own candidate alone: the own cell's
// reservoir there, weighed with its M, made fireflies (its samples' weight carries p̂_p / p̂_q),
// and weighed with 1 it raised night_market's raw relMSE (README, "One reservoir per 2×2
// pixels").
Reservoir resample_for_pixel(ShadingPoint p, RestirSurface surface, uvec2 pixel, uvec2 cell) {
  uvec2 found;
  RestirSurface q_surface;
  Reservoir r = reservoir_empty();
  if (similar_cell(pixel, surface, cell, found, q_surface)) {
    r = reservoir_unpack(reservoirs_in.r[restir_index(found)]);
  }
  ShadingPoint q = restir_shading_point(q_surface, frame_constants.frame.camera_position.xyz);
  float confidence = max(r.M, 0.0);
  uint rng = frame_rng(pixel, kRestirRngShadeCanonical);
  Reservoir out_r = reservoir_empty();
  if (reservoir_has_sample(r)) {
    GpuLight light = restir_sample_light(r.selected);
    float target_p = restir_target_with_light(p, r.selected, light);
    float target_q = restir_target_with_light(q, r.selected, light);
    float m = safe_ratio(confidence * target_q, confidence * target_q + target_p);
    reservoir_merge(out_r, r, m, target_p, rng_next_float(rng));
  } else {
    out_r.M = confidence;
  }
  LightSample y;
  float pdf;
  bool drawn = own_light_candidate(p, rng, y, pdf);
  float u_pick = rng_next_float(rng);
  float weight = 0.0;
  if (drawn) {
    GpuLight light = restir_sample_light(y);
    y.target_pdf = restir_target_with_light(p, y, light);
    float target_q = restir_target_with_light(q, y, light);
    float m = safe_ratio(y.target_pdf, confidence * target_q + y.target_pdf);
    weight = m * safe_ratio(y.target_pdf, pdf);
  }
  reservoir_update(out_r, y, weight, u_pick);
  reservoir_finalize(out_r);
  return out_r;
}

void shade_main() {
  uvec2 pixel;
  if (!restir_pixel(pixel)) return;
  uint index = restir_pixel_index(pixel);
  // The pixel's cell in the reservoir grid (itself with one reservoir per pixel).
  uvec2 cell = pixel / restir_stride();
  uint cell_index = restir_index(cell);
  RestirSurface surface = restir_surface_fetch(restir_surfaces, index);
  Reservoir r = reservoir_unpack(reservoirs_in.r[cell_index]);
  vis_host_begin(index);
  vec3 value;
  bool valid = restir_surface_valid(surface);
  if (push.debug_view != kRestirDebugNone) {
    value = debug_view(push.debug_view, pixel, cell_index, r, valid);
  } else if (!valid) {
    value = env_sky_radiance(frame_constants.frame, pixel);
  } else {
    value = imageLoad(gbuffer_emission_metallic, ivec2(pixel)).rgb;
    ShadingPoint p = restir_shading_point(surface, frame_constants.frame.camera_position.xyz);
    if (restir_stride() > 1u && pixel != restir_representative(cell)) {
      r = resample_for_pixel(p, surface, pixel, cell);
    }
    if (reservoir_has_sample(r)) {
      vec2 uv = vec2(r.selected.u, r.selected.v);
      vec3 c = restir_contribution(p, r.selected.light_index, uv);
      if (c != vec3(0.0)) {
        bool visible;
        vec3 y = restir_light_position(p, r.selected.light_index, uv);
        if (reuse_visibility(r)) {
          visible = reservoir_known_visible(r);
        } else {
          visible = vis_visible(p.x, y);
#ifndef LANTERN_VISIBILITY_HOST_EMIT  // the resolve variant writes the host's verdict
          if (push.visibility_reuse > 0u) {
            // The verdict travels with the sample into the next frame's history.
            reservoir_set_visibility(r, true, visible);
            reservoirs_in.r[cell_index] = reservoir_pack(r);
          }
#endif
        }
        if (visible) {
          // The media's transmittance along the shadow ray, unbiased and independent of the
          // resampling (its own random stream): the target ignored it, the shading does not.
          uint rng = frame_rng(pixel, kRestirRngShadeMedia);
          value += c * r.W * scene_transmittance_between(p.x, y, rng);
        }
      }
    }
  }
  // Never write NaN/Inf: a non-finite value counts as black.
  if (!(is_finite(value.x) && is_finite(value.y) && is_finite(value.z))) value = vec3(0.0);
  hdr.pixels[index] = vec4(max(value, vec3(0.0)), 1.0);
}

#ifdef LANTERN_VISIBILITY_HOST_RESOLVE
// Host visibility, after visibility.host: where the emit variant's ray was blocked, the pixel is
// what main() writes for a blocked sample (the G-buffer emission), and with visibility reuse the
// verdict goes into the reservoir as main() stores it. Pixels without a ray keep the emit
// variant's value.
void resolve_main() {
  uvec2 pixel;
  if (!restir_pixel(pixel)) return;
  uint index = restir_pixel_index(pixel);
  HostShadowRay ray = host_rays.r[index];
  if (!host_ray_traced(ray)) return;
  bool visible = host_ray_visible(ray);
  if (push.visibility_reuse > 0u) {  // one reservoir per pixel (RestirSettings)
    uint cell_index = restir_index(pixel / restir_stride());
    Reservoir r = reservoir_unpack(reservoirs_in.r[cell_index]);
    reservoir_set_visibility(r, true, visible);
    reservoirs_in.r[cell_index] = reservoir_pack(r);
  }
  if (!visible) {
    vec3 value = imageLoad(gbuffer_emission_metallic, ivec2(pixel)).rgb;
    if (!(is_finite(value.x) && is_finite(value.y) && is_finite(value.z))) value = vec3(0.0);
    hdr.pixels[index] = vec4(max(value, vec3(0.0)), 1.0);
  }
}
#endif

void main() {
#ifdef LANTERN_VISIBILITY_HOST_RESOLVE
  resolve_main();
#else
  shade_main();
#endif
}
