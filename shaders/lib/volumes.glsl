// The scene's participating media as every pass reads them (included by lib/scene_buffers.glsl):
// the volume records, majorant cells and brick values (shared/volume.h, shared/volume_grid.h;
// one zeroed stand-in element each without volumes), the grid fetch hooks and the tracking
// callback the shared code calls, and scene_transmittance, the unbiased transmittance of all
// media along a segment. frame_constants.frame.media.x volumes: 0 makes every transmittance 1
// without a loop, so levels without media pay one uniform branch.
#ifndef LANTERN_LIB_VOLUMES_GLSL
#define LANTERN_LIB_VOLUMES_GLSL

#include "shared/volume.h"

layout(std430, binding = kSceneVolumes) restrict readonly buffer VolumeBuffer {
  GpuVolume v[];
} scene_volumes;
layout(std430, binding = kSceneVolumeCells) restrict readonly buffer VolumeCellBuffer {
  GpuVolumeCell c[];
} scene_volume_cells;
layout(std430, binding = kSceneVolumeValues) restrict readonly buffer VolumeValueBuffer {
  float v[];
} scene_volume_values;

GpuVolumeCell volume_fetch_cell(uint i) { return scene_volume_cells.c[i]; }
float volume_fetch_value(uint i) { return scene_volume_values.v[i]; }

#include "shared/volume_grid.h"

// sigma_t (1/m per channel) of volume `medium` at index-space point p.
vec3 medium_extinction(uint medium, vec3 p) {
  GpuVolume v = scene_volumes.v[medium];
  return volume_extinction(v, volume_density_index(v, p));
}

// Transmittance of every medium along origin + t dir, t in [t_min, t_max] (dir unit, world
// space): the product of each volume's residual ratio tracking estimate over its majorant cells
// (unbiased; exact where a cell is homogeneous, since the control is then the extinction).
vec3 scene_transmittance_segment(vec3 origin, vec3 dir, float t_min, float t_max,
                                 inout uint rng) {
  vec3 transmittance = vec3(1.0);
  uint count = frame_constants.frame.media.x;
  for (uint i = 0u; i < count; ++i) {
    GpuVolume v = scene_volumes.v[i];
    vec3 o = (v.world_to_index * vec4(origin, 1.0)).xyz;
    vec3 d = mat3(v.world_to_index) * dir;
    transmittance *= volume_transmittance_residual(i, v, o, d, t_min, t_max, 0.0, rng);
  }
  return transmittance;
}

// The same over t in [0, t_max].
vec3 scene_transmittance(vec3 origin, vec3 dir, float t_max, inout uint rng) {
  return scene_transmittance_segment(origin, dir, 0.0, t_max, rng);
}

// The same along the segment a -> b.
vec3 scene_transmittance_between(vec3 a, vec3 b, inout uint rng) {
  if (frame_constants.frame.media.x == 0u) return vec3(1.0);
  vec3 d = b - a;
  float len = length(d);
  if (!(len > 0.0)) return vec3(1.0);
  return scene_transmittance(a, d / len, len, rng);
}

#endif
