// restir.temporal: merges each pixel's initial reservoir with last frame's final reservoir at the
// reprojected pixel (motion vector; with kRestirFlagTemporalPermutation a neighbour of it,
// restir_permuted_history_pixel; then up to 3 jittered retries within 1.5 px), when the
// surface there passes the disocclusion test (relative view depth against the depth the previous
// camera saw this point at, normal, material, roughness). The history sample's light is remapped
// through light_previous_to_current (an environment sample stays one); a removed light drops the
// history sample (M kept, as for an empty history reservoir). History confidence M is capped
// (push.m_cap, lower where the point moves: restir_history_m_cap with push.m_cap_moving). MIS
// weights per push.bias_correction. Optional boiling filter over the tile.
// Reads: restir_surfaces, surfaces_history, reservoirs_in, reservoirs_history, gbuffer_motion
// (xy: the reprojection; zw: the point's own motion, for the cap),
// light_previous_to_current, frame constants, lights, environment (env_*).
// Writes: reservoirs_out, temporal_status.
// History: "restir.surfaces" and "restir.reservoirs" of last frame; without
// kRestirFlagHistoryValid the history bindings are stand-ins and are not read.
// Dispatch: one workgroup per tile (lib/pixel_groups.glsl's shape), in interleaved row bands on
// CPU devices (push.tile_bands), else shuffled (push.tile_stride): pixel_tile_origin.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "restir/restir_common.glsl"

// The two domains, canonical (0) and history (1), as named values rather than a loop-indexed
// private array (which lavapipe spills; night_market 320x180: restir.temporal 0.85-0.96x of the
// array's time with these, 6 rounds alternating in one run).
Reservoir g_canonical;
ShadingPoint g_canonical_point;
Reservoir g_history;
ShadingPoint g_history_point;
Reservoir combine_domain_reservoir(uint j) { return j == 0u ? g_canonical : g_history; }
float combine_domain_target(uint j, LightSample y) {
  return restir_target(j == 0u ? g_canonical_point : g_history_point, y);
}
// Pairwise MIS's three evaluations with each sample's light fetched once.
#define LANTERN_COMBINE_PAIRWISE_TARGETS
vec3 combine_pairwise_targets(uint j, LightSample y_c, LightSample y_h) {
  GpuLight light_c = restir_sample_light(y_c);
  GpuLight light_h = restir_sample_light(y_h);
  return vec3(restir_target_with_light(g_history_point, y_c, light_c),
              restir_target_with_light(g_history_point, y_h, light_h),
              restir_target_with_light(g_canonical_point, y_h, light_h));
}
#include "restir/restir_reuse.glsl"

layout(binding = PASS_BINDING(0), rgba32f) readonly uniform image2D gbuffer_motion;
layout(binding = PASS_BINDING(1)) uniform utextureBuffer restir_surfaces;
layout(binding = PASS_BINDING(2)) uniform utextureBuffer surfaces_history;
layout(binding = PASS_BINDING(3)) uniform utextureBuffer reservoirs_in;
layout(binding = PASS_BINDING(4)) uniform utextureBuffer reservoirs_history;
layout(std430, binding = PASS_BINDING(5)) writeonly buffer ReservoirOut {
  PackedReservoir r[];
} reservoirs_out;
layout(std430, binding = PASS_BINDING(6)) writeonly buffer StatusOut {
  uint status[];
} temporal_status;

shared float s_weights[kPixelGroupThreads];

// Finds last frame's pixel for this surface along `motion` (the G-buffer motion's xy); -1 when
// disoccluded. status: kRestirStatus*.
ivec2 find_history(uvec2 pixel, vec2 motion, RestirSurface surface, inout uint rng,
                   out uint status) {
  status = kRestirStatusNoHistory;
  ivec2 size = ivec2(restir_size());
  if (!(is_finite(motion.x) && is_finite(motion.y))) return ivec2(-1);
  vec2 previous = vec2(pixel) + 0.5 + motion;
  vec4 clip = frame_constants.frame.prev_view_proj * vec4(restir_surface_position(surface), 1.0);
  float expected_depth = clip.w;  // Vulkan perspective: clip w = linear view depth
  for (uint t = 0u; t < kRestirTemporalTries; ++t) {
    vec2 jitter = t == 0u ? vec2(0.0) : (rng_next_vec2(rng) - 0.5) * 3.0;
    ivec2 q = ivec2(floor(previous + jitter));
    if (t == 0u && (push.flags & kRestirFlagTemporalPermutation) != 0u) {
      q = restir_permuted_history_pixel(q, push.permutation_bits);
    }
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    RestirSurface old = restir_surface_fetch(surfaces_history, q.y * size.x + q.x);
    if (restir_surfaces_similar(surface, expected_depth, old, push.similarity)) {
      status = kRestirStatusReprojected + t;
      return q;
    }
  }
  return ivec2(-1);
}

void main() {
  uvec2 pixel;
  bool inside = restir_pixel(pixel);
  uint index = inside ? restir_index(pixel) : 0u;
  Reservoir r = reservoir_empty();
  uint status = kRestirStatusNoHistory;
  if (inside) {
    RestirSurface surface = restir_surface_fetch(restir_surfaces, index);
    r = reservoir_unpack(reservoir_fetch(reservoirs_in, index));
    if (restir_surface_valid(surface) && (push.flags & kRestirFlagHistoryValid) != 0u) {
      uint rng = frame_rng(pixel, kRestirRngTemporal);
      // xy: the reprojection; zw: the point's own motion, for the cap below.
      vec4 motions = imageLoad(gbuffer_motion, ivec2(pixel));
      ivec2 q = find_history(pixel, motions.xy, surface, rng, status);
      if (q.x >= 0) {
        uint q_index = uint(q.y) * restir_size().x + uint(q.x);
        Reservoir history = reservoir_unpack(reservoir_fetch(reservoirs_history, q_index));
        reservoir_age_one_frame(history);
        // Visibility reuse only along a direct reprojection (a jittered retry or a permuted
        // pixel is another point).
        if (status != kRestirStatusReprojected ||
            (push.flags & kRestirFlagTemporalPermutation) != 0u) {
          reservoir_set_visibility(history, false, false);
        }
        // A removed light (or an empty history reservoir) leaves no sample but keeps M: the
        // history domain produced "nothing" this time, and the canonical sample's MIS weight must
        // not depend on that outcome. (Zeroing M here skipped the merge exactly when the history
        // was empty: +7% on cornell_lights' lit surfaces, +18% with 1 candidate.)
        uint light = history.selected.light_index;
        if (light != kInvalidLight && light != kEnvironmentLight) {
          light = scene_light_from_previous(light);
          if (light >= restir_light_count()) light = kInvalidLight;
        }
        reservoir_remap_light(history, light);
        reservoir_cap_m(history,
                        restir_history_m_cap(push.m_cap, push.m_cap_moving, motions.zw));
        if (history.M > 0.0) {
          g_canonical = r;
          g_canonical_point =
              restir_shading_point(surface, frame_constants.frame.camera_position.xyz);
          g_history = history;
          g_history_point = restir_shading_point(restir_surface_fetch(surfaces_history, q_index),
                                                 frame_constants.frame.prev_camera_position.xyz);
          r = restir_combine(2u, push.bias_correction, rng);
        }
      }
    }
  }

  // Boiling filter: drop reservoirs whose weight is far above the tile's mean non-zero weight.
  if (push.boiling_filter > 0.0) {
    uint local = gl_LocalInvocationIndex;
    s_weights[local] = reservoir_has_sample(r) ? r.W * r.selected.target_pdf : 0.0;
    barrier();
    float sum = 0.0;
    float count = 0.0;
    for (uint i = 0u; i < kPixelGroupThreads; ++i) {
      float w = s_weights[i];
      sum += w;
      count += w > 0.0 ? 1.0 : 0.0;
    }
    float multiplier = mix(32.0, 2.0, clamp(push.boiling_filter, 0.0, 1.0));
    if (count > 0.0 && s_weights[local] > multiplier * sum / count) r = reservoir_empty();
  }
  if (!inside) return;
  reservoirs_out.r[index] = reservoir_pack(r);
  temporal_status.status[index] = status;
}
