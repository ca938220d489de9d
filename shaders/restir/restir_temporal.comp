// restir.temporal (per cell of the reservoir grid, restir_cell: a pixel, or a block's
// representative with push.reservoir_stride > 1, whose motion it reprojects into last frame's
// cells): merges each pixel's initial reservoir with last frame's final reservoir at the
// reprojected pixel (motion vector; with kRestirFlagTemporalPermutation a neighbour of it,
// restir_permuted_history_pixel; then up to 3 jittered retries within 1.5 px), when the
// surface there passes the disocclusion test (relative view depth against the depth the previous
// camera saw this point at, normal, material, roughness), and with push.temporal_neighbours more
// of last frame's final reservoirs drawn in a disk of push.radius pixels around the reprojected
// pixel that pass the same test (push.boost_neighbours more where the reprojected pixel itself
// fails it: a disocclusion finds the surface's history beside it): spatiotemporal reuse in one
// pass, spatial reuse from last frame's neighbours (RTXDI's fused mode), where restir.spatial
// reuses this frame's. Each history sample's light is remapped through
// light_previous_to_current (an environment sample stays one); a removed light drops the
// history sample (M kept, as for an empty history reservoir). Each history reservoir's
// confidence M is capped (push.m_cap, lower where the point moves: restir_history_m_cap with
// push.m_cap_moving). MIS weights per push.bias_correction. Optional boiling filter over the tile.
// Reads: restir_surfaces, surfaces_history, reservoirs_in, reservoirs_history, gbuffer_motion
// (xy: the reprojection; zw: the point's own motion, for the cap),
// light_previous_to_current, frame constants, lights, environment (env_*).
// Writes: reservoirs_out, temporal_status (the reprojected pixel's outcome).
// History: "restir.surfaces" and "restir.reservoirs" of last frame; without
// kRestirFlagHistoryValid the history bindings are stand-ins and are not read.
// Dispatch: one workgroup per tile (lib/pixel_groups.glsl's shape), in interleaved row bands on
// CPU devices (push.tile_bands), else shuffled (push.tile_stride): pixel_tile_origin.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "restir/restir_common.glsl"

// The domains: the canonical pixel (0) and domain 1 (the reprojected pixel, the only history
// domain without temporal_neighbours) read and decoded once into named values, as the `balance`
// and `none` loops ask for a domain several times (a loop-indexed private array of decoded
// domains is what lavapipe spills: night_market 320x180, restir.temporal 0.85-0.96x of such an
// array's time with named domains, 6 rounds alternating); domains j >= 2 as pixel indices into
// the history, read and decoded at each use (pairwise MIS: once).
Reservoir g_canonical;
ShadingPoint g_canonical_point;
GpuLight g_canonical_light;  // pairwise MIS only
uint g_history_first;  // domain 1's pixel index in the history
Reservoir g_history;
ShadingPoint g_history_point;
uint g_history_pixel[kRestirMaxNeighbours + 2u];
float g_history_m_cap;
Reservoir history_reservoir(uint index, bool keep_visibility);
ShadingPoint history_point(uint index);
Reservoir combine_domain_reservoir(uint j) {
  if (j == 0u) return g_canonical;
  return j == 1u ? g_history : history_reservoir(g_history_pixel[j], false);
}
ShadingPoint domain_point(uint j) {
  if (j == 0u) return g_canonical_point;
  return j == 1u ? g_history_point : history_point(g_history_pixel[j]);
}
float combine_domain_target(uint j, LightSample y) { return restir_target(domain_point(j), y); }
// Pairwise MIS's three evaluations for domain j: its point decoded once, the canonical sample's
// light fetched once per pixel, domain j's once for both points.
#define LANTERN_COMBINE_PAIRWISE_TARGETS
vec3 combine_pairwise_targets(uint j, LightSample y_c, LightSample y_j) {
  ShadingPoint p = domain_point(j);
  GpuLight light_j = restir_sample_light(y_j);
  return vec3(restir_target_with_light(p, y_c, g_canonical_light),
              restir_target_with_light(p, y_j, light_j),
              restir_target_with_light(g_canonical_point, y_j, light_j));
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

// The reservoir of history pixel `index` as this frame sees it: a frame older, its light
// remapped (a removed light, or an empty history reservoir, leaves no sample but keeps M: that
// domain produced "nothing" this time, and the canonical sample's MIS weight must not depend on
// that outcome; zeroing M there skipped the merge exactly when the history was empty: +7% on
// cornell_lights' lit surfaces, +18% with 1 candidate), M capped, and its visibility verdict
// dropped unless `keep_visibility` (the direct reprojection: a jittered retry, a permuted pixel
// or a neighbour is another point).
Reservoir history_reservoir(uint index, bool keep_visibility) {
  Reservoir h = reservoir_unpack(reservoir_fetch(reservoirs_history, index));
  reservoir_age_one_frame(h);
  if (!keep_visibility) reservoir_set_visibility(h, false, false);
  uint light = h.selected.light_index;
  if (light != kInvalidLight && light != kEnvironmentLight) {
    light = scene_light_from_previous(light);
    if (light >= restir_light_count()) light = kInvalidLight;
  }
  reservoir_remap_light(h, light);
  reservoir_cap_m(h, g_history_m_cap);
  return h;
}

// History pixel `index`'s surface, seen from last frame's camera.
ShadingPoint history_point(uint index) {
  return restir_shading_point(restir_surface_fetch(surfaces_history, index),
                              frame_constants.frame.prev_camera_position.xyz);
}

// Finds last frame's cell for this surface at `reprojected` (the representative pixel's centre
// plus the G-buffer motion's xy, in cells): the cell whose surface passed the disocclusion test,
// -1 when none did. status: kRestirStatus*. expected_depth: the depth the previous camera saw
// this point at.
ivec2 find_history(vec2 reprojected, RestirSurface surface, float expected_depth, inout uint rng,
                   out uint status) {
  status = kRestirStatusNoHistory;
  ivec2 size = ivec2(restir_grid_size());
  for (uint t = 0u; t < kRestirTemporalTries; ++t) {
    vec2 jitter = t == 0u ? vec2(0.0) : (rng_next_vec2(rng) - 0.5) * 3.0;
    ivec2 q = ivec2(floor(reprojected + jitter));
    if (t == 0u && (push.flags & kRestirFlagTemporalPermutation) != 0u) {
      q = restir_permuted_history_pixel(q, push.permutation_bits);
    }
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    RestirSurface old = restir_surface_fetch(surfaces_history, restir_index(uvec2(q)));
    if (restir_surfaces_similar(surface, expected_depth, old, push.similarity)) {
      status = kRestirStatusReprojected + t;
      return q;
    }
  }
  return ivec2(-1);
}

// Adds to the history domains (g_history_first, then g_history_pixel[count...]) up to `tries` of
// last frame's pixels drawn uniformly in a disk of push.radius pixels around `centre` whose
// surfaces pass the disocclusion test, other than `skip` (the domain already taken, or -1).
// Returns the new count.
uint add_history_neighbours(ivec2 centre, ivec2 skip, uint tries, RestirSurface surface,
                            float expected_depth, uint count, inout uint rng) {
  for (uint t = 0u; t < tries; ++t) {
    uint q_index;
    if (!restir_disk_neighbour(centre, skip, rng, q_index)) continue;
    if (!restir_surfaces_similar(surface, expected_depth,
                                 restir_surface_fetch(surfaces_history, q_index),
                                 push.similarity)) {
      continue;
    }
    if (count == 1u) {
      g_history_first = q_index;
    } else {
      g_history_pixel[count] = q_index;
    }
    ++count;
  }
  return count;
}

void main() {
  uvec2 cell;
  bool inside = restir_cell(cell);
  uint index = inside ? restir_index(cell) : 0u;
  Reservoir r = reservoir_empty();
  uint status = kRestirStatusNoHistory;
  if (inside) {
    RestirSurface surface = restir_surface_fetch(restir_surfaces, index);
    r = reservoir_unpack(reservoir_fetch(reservoirs_in, index));
    if (restir_surface_valid(surface) && (push.flags & kRestirFlagHistoryValid) != 0u) {
      uint rng = frame_rng(cell, kRestirRngTemporal);
      // The representative pixel's motion. xy: the reprojection; zw: the point's own motion, for
      // the cap below.
      uvec2 pixel = restir_representative(cell);
      vec4 motions = imageLoad(gbuffer_motion, ivec2(pixel));
      vec4 clip =
          frame_constants.frame.prev_view_proj * vec4(restir_surface_position(surface), 1.0);
      float expected_depth = clip.w;  // Vulkan perspective: clip w = linear view depth
      bool reprojects = is_finite(motions.x) && is_finite(motions.y);
      // Clamped far outside any image, so the integer pixels below cannot overflow.
      // In cells (last frame's cell of that pixel: its representative may have been another).
      vec2 reprojected = clamp((vec2(pixel) + 0.5 + motions.xy) / float(restir_stride()),
                               vec2(-65536.0), vec2(65536.0));
      ivec2 q = reprojects ? find_history(reprojected, surface, expected_depth, rng, status)
                           : ivec2(-1);
      uint count = 1u;
      if (q.x >= 0) {
        g_history_first = restir_index(uvec2(q));
        count = 2u;
      }
      if (reprojects && push.temporal_neighbours > 0u) {
        uint tries = push.temporal_neighbours + (q.x < 0 ? push.boost_neighbours : 0u);
        count = add_history_neighbours(ivec2(floor(reprojected)), q,
                                       min(tries, kRestirMaxNeighbours), surface,
                                       expected_depth, count, rng);
      }
      if (count > 1u) {
        g_canonical = r;
        g_canonical_point =
            restir_shading_point(surface, frame_constants.frame.camera_position.xyz);
        if (push.bias_correction == kBiasCorrectionPairwise) {
          g_canonical_light = restir_sample_light(r.selected);
        }
        g_history_m_cap = restir_history_m_cap(push.m_cap, push.m_cap_moving, motions.zw);
        // Visibility reuse only along a direct reprojection.
        g_history = history_reservoir(g_history_first,
                                      status == kRestirStatusReprojected &&
                                          (push.flags & kRestirFlagTemporalPermutation) == 0u);
        g_history_point = history_point(g_history_first);
        r = restir_combine(count, push.bias_correction, rng);
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
