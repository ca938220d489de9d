// restir.spatial (pass push.spatial_pass of N): merges each pixel's reservoir with up to
// push.neighbours neighbours drawn uniformly in a disk of push.radius pixels, skipping neighbours
// whose surface is dissimilar (depth, normal, material, roughness). Pixels short of history
// (M below push.short_history_m, e.g. just disoccluded) draw push.boost_neighbours more
// neighbours. MIS weights per push.bias_correction (none O(k), pairwise O(k), balance O(k^2)
// target evaluations).
// Reads: restir_surfaces, reservoirs_in, frame constants, lights, environment (env_*).
// Writes: reservoirs_out.
// History: none (the last pass's output is the frame's final reservoirs, kept by the graph).
// Dispatch: one workgroup per 8x8 tile, shuffled (push.tile_stride).
#version 460
#extension GL_GOOGLE_include_directive : require

#include "restir/restir_reuse.glsl"

layout(std430, binding = PASS_BINDING(0)) readonly buffer SurfaceIn {
  RestirSurface s[];
} restir_surfaces;
layout(std430, binding = PASS_BINDING(1)) readonly buffer ReservoirIn {
  PackedReservoir r[];
} reservoirs_in;
layout(std430, binding = PASS_BINDING(2)) writeonly buffer ReservoirOut {
  PackedReservoir r[];
} reservoirs_out;

void main() {
  uvec2 pixel;
  if (!restir_pixel(pixel)) return;
  uint index = restir_index(pixel);
  RestirSurface surface = restir_surfaces.s[index];
  Reservoir r = reservoir_unpack(reservoirs_in.r[index]);
  if (!restir_surface_valid(surface)) {
    reservoirs_out.r[index] = reservoir_pack(r);
    return;
  }
  vec3 camera = frame_constants.frame.camera_position.xyz;
  g_reservoirs[0] = r;
  g_points[0] = restir_shading_point(surface, camera);
  uint rng = frame_rng(pixel, kRestirRngSpatial + push.spatial_pass);
  uint tries = push.neighbours + (r.M < float(push.short_history_m) ? push.boost_neighbours : 0u);
  tries = min(tries, kRestirMaxNeighbours);
  ivec2 size = ivec2(restir_size());
  float depth = restir_surface_depth(surface);
  uint count = 1u;
  for (uint t = 0u; t < tries; ++t) {
    vec2 u = rng_next_vec2(rng);
    float radius = push.radius * sqrt(u.x);
    float angle = kTwoPi * u.y;
    ivec2 q = ivec2(pixel) + ivec2(round(radius * vec2(cos(angle), sin(angle))));
    if (q == ivec2(pixel) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    uint q_index = uint(q.y) * restir_size().x + uint(q.x);
    RestirSurface other = restir_surfaces.s[q_index];
    if (!restir_surfaces_similar(surface, depth, other, push.similarity)) continue;
    g_reservoirs[count] = reservoir_unpack(reservoirs_in.r[q_index]);
    g_points[count] = restir_shading_point(other, camera);
    ++count;
  }
  if (count > 1u) r = restir_combine(count, push.bias_correction, rng);
  reservoirs_out.r[index] = reservoir_pack(r);
}
