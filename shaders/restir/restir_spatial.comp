// restir.spatial (pass push.spatial_pass of N; per cell of the reservoir grid, restir_cell: a
// pixel, or a block's representative with push.reservoir_stride > 1, radius in cells): merges
// each pixel's reservoir with up to push.neighbours neighbours drawn uniformly in a disk of
// push.radius pixels, skipping neighbours whose surface is dissimilar (depth, normal, material,
// roughness). Pixels short of history (M below push.short_history_m, e.g. just disoccluded) draw
// push.boost_neighbours more neighbours. MIS weights per push.bias_correction (none O(k),
// pairwise O(k), balance O(k^2) target evaluations).
// Reads: restir_surfaces, reservoirs_in, frame constants, lights, environment (env_*).
// Writes: reservoirs_out.
// History: none (the last pass's output is the frame's final reservoirs, kept by the graph).
// Dispatch: one workgroup per tile (lib/pixel_groups.glsl's shape), in interleaved row bands on
// CPU devices (push.tile_bands), else shuffled (push.tile_stride): pixel_tile_origin.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "restir/restir_common.glsl"

layout(binding = PASS_BINDING(0)) uniform utextureBuffer restir_surfaces;
layout(binding = PASS_BINDING(1)) uniform utextureBuffer reservoirs_in;
layout(std430, binding = PASS_BINDING(2)) writeonly buffer ReservoirOut {
  PackedReservoir r[];
} reservoirs_out;

// The domains: the canonical pixel (decoded once) and neighbours kept as pixel indices, decoded
// at each p̂ evaluation (night_market 320x180: restir.spatial 0.73x the time of a private array
// of decoded points, A/B in one run).
uint g_domain_pixel[kRestirMaxNeighbours + 1u];
Reservoir g_canonical;
ShadingPoint g_canonical_point;
vec3 g_camera;
Reservoir combine_domain_reservoir(uint j) {
  if (j == 0u) return g_canonical;
  Reservoir r = reservoir_unpack(reservoir_fetch(reservoirs_in, g_domain_pixel[j]));
  reservoir_set_visibility(r, false, false);  // its visibility was seen from another surface
  return r;
}
ShadingPoint domain_point(uint j) {
  return j == 0u ? g_canonical_point
                 : restir_shading_point(restir_surface_fetch(restir_surfaces, g_domain_pixel[j]),
                                        g_camera);
}
float combine_domain_target(uint j, LightSample y) { return restir_target(domain_point(j), y); }
// Pairwise MIS's three evaluations for neighbour j: its point decoded once, the canonical
// sample's light fetched once per pixel (g_canonical_light), neighbour j's once for both points.
GpuLight g_canonical_light;
#define LANTERN_COMBINE_PAIRWISE_TARGETS
vec3 combine_pairwise_targets(uint j, LightSample y_c, LightSample y_j) {
  ShadingPoint p = domain_point(j);
  GpuLight light_j = restir_sample_light(y_j);
  return vec3(restir_target_with_light(p, y_c, g_canonical_light),
              restir_target_with_light(p, y_j, light_j),
              restir_target_with_light(g_canonical_point, y_j, light_j));
}
#include "restir/restir_reuse.glsl"

void main() {
  uvec2 cell;
  if (!restir_cell(cell)) return;
  uint index = restir_index(cell);
  RestirSurface surface = restir_surface_fetch(restir_surfaces, index);
  Reservoir r = reservoir_unpack(reservoir_fetch(reservoirs_in, index));
  if (!restir_surface_valid(surface)) {
    reservoirs_out.r[index] = reservoir_pack(r);
    return;
  }
  vec3 camera = frame_constants.frame.camera_position.xyz;
  g_camera = camera;
  g_canonical = r;
  g_canonical_point = restir_shading_point(surface, camera);
  g_canonical_light = restir_sample_light(r.selected);
  g_domain_pixel[0] = index;
  uint rng = frame_rng(cell, kRestirRngSpatial + push.spatial_pass);
  uint tries = push.neighbours + (r.M < float(push.short_history_m) ? push.boost_neighbours : 0u);
  tries = min(tries, kRestirMaxNeighbours);
  float depth = restir_surface_depth(surface);
  uint count = 1u;
  for (uint t = 0u; t < tries; ++t) {
    uint q_index;
    if (!restir_disk_neighbour(ivec2(cell), ivec2(cell), rng, q_index)) continue;
    RestirSurface other = restir_surface_fetch(restir_surfaces, q_index);
    if (!restir_surfaces_similar(surface, depth, other, push.similarity)) continue;
    g_domain_pixel[count] = q_index;
    ++count;
  }
  if (count > 1u) r = restir_combine(count, push.bias_correction, rng);
  reservoirs_out.r[index] = reservoir_pack(r);
}
