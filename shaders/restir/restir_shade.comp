// restir.shade: per pixel, the final reservoir's sample shaded with one visibility ray:
// radiance = G-buffer emission + c(x, y) V(x, y) W (c = BRDF x cos x Le x G, shared/light_eval.h);
// sky pixels show the environment map along their camera ray (lib/environment.glsl). With a
// debug view (push.debug_view) writes that view instead. Never writes NaN/Inf.
// Reads: restir_surfaces, reservoirs_in (the final reservoirs), gbuffer emission_metallic and
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

void shade_main() {
  uvec2 pixel;
  if (!restir_pixel(pixel)) return;
  uint index = restir_index(pixel);
  RestirSurface surface = restir_surface_fetch(restir_surfaces, index);
  Reservoir r = reservoir_unpack(reservoirs_in.r[index]);
  vis_host_begin(index);
  vec3 value;
  bool valid = restir_surface_valid(surface);
  if (push.debug_view != kRestirDebugNone) {
    value = debug_view(push.debug_view, pixel, index, r, valid);
  } else if (!valid) {
    value = env_sky_radiance(frame_constants.frame, pixel);
  } else {
    value = imageLoad(gbuffer_emission_metallic, ivec2(pixel)).rgb;
    if (reservoir_has_sample(r)) {
      ShadingPoint p = restir_shading_point(surface, frame_constants.frame.camera_position.xyz);
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
            reservoirs_in.r[index] = reservoir_pack(r);
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
  uint index = restir_index(pixel);
  HostShadowRay ray = host_rays.r[index];
  if (!host_ray_traced(ray)) return;
  bool visible = host_ray_visible(ray);
  if (push.visibility_reuse > 0u) {
    Reservoir r = reservoir_unpack(reservoirs_in.r[index]);
    reservoir_set_visibility(r, true, visible);
    reservoirs_in.r[index] = reservoir_pack(r);
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
