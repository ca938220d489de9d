// Benchmark kernel (tests/volume/volume_lookup_bench.cpp): the cost of trilinear density lookups
// in one grid stored two ways — the project's 8^3 bricks with a majorant cell box
// (shared/volume_grid.h volume_density_index) or NanoVDB's tree read through PNanoVDB.h's
// accessor (kNanoVdb). Each thread marches push.steps points half a voxel apart along a random
// ray through the index box (what tracking does) and writes the sum of the densities it read,
// so both layouts must return the same sums.
#version 460
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;
layout(constant_id = 0) const bool kNanoVdb = false;

layout(std430, binding = 0) restrict readonly buffer NanoGrid { uint pnanovdb_buf_data[]; };
#define PNANOVDB_GLSL
#include "nanovdb/PNanoVDB.h"

#include "shared/rng.h"
#include "shared/volume.h"

layout(std430, binding = 1) restrict readonly buffer Cells { GpuVolumeCell c[]; } bench_cells;
layout(std430, binding = 2) restrict readonly buffer Values { float v[]; } bench_values;
layout(std430, binding = 3) restrict readonly buffer Record { GpuVolume v; } bench_record;
layout(std430, binding = 4) restrict writeonly buffer Out { float sum[]; } bench_out;

GpuVolumeCell volume_fetch_cell(uint i) { return bench_cells.c[i]; }
float volume_fetch_value(uint i) { return bench_values.v[i]; }
vec3 medium_extinction(uint medium, vec3 p) { return vec3(0.0); }
#include "shared/volume_grid.h"

layout(push_constant) uniform Push {
  vec4 box_min;  // index-space box the rays cross
  vec4 box_max;
  uint steps;
  uint threads;
} push;

float nano_voxel(pnanovdb_buf_t buf, inout pnanovdb_readaccessor_t acc, ivec3 ijk) {
  return pnanovdb_read_float(
      buf, pnanovdb_readaccessor_get_value_address(PNANOVDB_GRID_TYPE_FLOAT, buf, acc, ijk));
}

// Trilinear between the eight voxel centres around p (the same convention as the bricks).
float nano_density(pnanovdb_buf_t buf, inout pnanovdb_readaccessor_t acc, vec3 p) {
  vec3 base = floor(p);
  vec3 f = p - base;
  ivec3 b = ivec3(base);
  float c000 = nano_voxel(buf, acc, b);
  float c100 = nano_voxel(buf, acc, b + ivec3(1, 0, 0));
  float c010 = nano_voxel(buf, acc, b + ivec3(0, 1, 0));
  float c110 = nano_voxel(buf, acc, b + ivec3(1, 1, 0));
  float c001 = nano_voxel(buf, acc, b + ivec3(0, 0, 1));
  float c101 = nano_voxel(buf, acc, b + ivec3(1, 0, 1));
  float c011 = nano_voxel(buf, acc, b + ivec3(0, 1, 1));
  float c111 = nano_voxel(buf, acc, b + ivec3(1, 1, 1));
  return mix(mix(mix(c000, c100, f.x), mix(c010, c110, f.x), f.y),
             mix(mix(c001, c101, f.x), mix(c011, c111, f.x), f.y), f.z);
}

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (id >= push.threads) return;
  uint rng = rng_init(uvec2(id, 7u), 0u, 0x4e56u, 0u);
  vec3 lo = push.box_min.xyz;
  vec3 hi = push.box_max.xyz;
  vec3 origin = mix(lo, hi, vec3(rng_next_float(rng), rng_next_float(rng), rng_next_float(rng)));
  vec3 target = mix(lo, hi, vec3(rng_next_float(rng), rng_next_float(rng), rng_next_float(rng)));
  vec3 dir = normalize(target - origin + vec3(1e-3));
  GpuVolume v = bench_record.v;
  pnanovdb_buf_t buf;
  buf.unused = 0u;
  pnanovdb_grid_handle_t grid;
  grid.address.byte_offset = 0u;
  pnanovdb_readaccessor_t acc;
  pnanovdb_readaccessor_init(acc, pnanovdb_tree_get_root(buf, pnanovdb_grid_get_tree(buf, grid)));
  float sum = 0.0;
  for (uint s = 0u; s < push.steps; ++s) {
    vec3 p = clamp(origin + (0.5 * float(s)) * dir, lo, hi);
    sum += kNanoVdb ? nano_density(buf, acc, p) : volume_density_index(v, p);
  }
  bench_out.sum[id] = sum;
}
