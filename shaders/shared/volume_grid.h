// A volume's grid as the GPU (and the CPU, runtime/volume/volume_grid.h) stores it: a box of
// majorant cells of 8^3 voxels, each with a 9^3 brick (its voxels and the first layer of its +x,
// +y, +z neighbours) or empty (all zero), and the trilinear sampling in
// index space that every volume pass uses. Memory is reached through two fetch functions: GLSL
// defines them before including this file; the C++ ones (below) read a VolumeGridView.
//   GpuVolumeCell volume_fetch_cell(uint i);  float volume_fetch_value(uint i)
// Cell and brick indices are absolute: several volumes share one cell and one value array
// (GpuVolume.cells.w is a volume's first cell; runtime::pack_volume_grid rebases the bricks).
#ifndef LANTERN_SHARED_VOLUME_GRID_H
#define LANTERN_SHARED_VOLUME_GRID_H

#include "shared/volume.h"

#ifdef __cplusplus
namespace lantern::gpu {
// The CPU's view of one volume's arrays (runtime/volume/volume_grid.h owns them).
struct VolumeGridView {
  const GpuVolumeCell* cells = nullptr;
  const float* values = nullptr;
};
inline GpuVolumeCell volume_fetch_cell(const VolumeGridView& grid, uint i) {
  return grid.cells[i];
}
inline float volume_fetch_value(const VolumeGridView& grid, uint i) {
  return grid.values[i];
}
}  // namespace lantern::gpu
#define LANTERN_VOLUME_GRID_PARAM const VolumeGridView &grid,
#define LANTERN_VOLUME_GRID grid,
#else
#define LANTERN_VOLUME_GRID_PARAM
#define LANTERN_VOLUME_GRID
#endif

LANTERN_BEGIN_SHARED

// The cell (local xyz, integer-valued) holding index-space point p; outside the box when any
// component is < 0 or >= cells.xyz.
LANTERN_FUNC vec3 volume_cell_of(GpuVolume v, vec3 p) {
  return floor((p - vec3(v.cell_origin)) / float(kVolumeBrickSize));
}

LANTERN_FUNC bool volume_cell_inside(GpuVolume v, vec3 cell) {
  return cell.x >= 0.0f && cell.y >= 0.0f && cell.z >= 0.0f && cell.x < float(v.cells.x) &&
         cell.y < float(v.cells.y) && cell.z < float(v.cells.z);
}

// Absolute index of an inside cell in the cell array.
LANTERN_FUNC uint volume_cell_index(GpuVolume v, vec3 cell) {
  uvec3 c = uvec3(cell);
  return v.cells.w + c.x + v.cells.x * (c.y + v.cells.y * c.z);
}

// Offset of brick-local voxel l (each component in [0, 8]) within a brick's 9^3 values.
LANTERN_FUNC uint volume_brick_offset(uvec3 l) {
  return l.x + kVolumeBrickEdge * (l.y + kVolumeBrickEdge * l.z);
}

// Where voxel ijk (integer-valued index coordinates) is stored: its index in the value array,
// in the brick of the cell holding it. False outside the cells or in an empty brick, where it
// (and, by construction of the bricks, every voxel outside the active region) reads 0.
LANTERN_FUNC bool volume_voxel_index(LANTERN_VOLUME_GRID_PARAM GpuVolume v, vec3 ijk,
                                     LANTERN_OUT(uint) index) {
  index = 0u;
  vec3 cell = volume_cell_of(v, ijk);
  if (!volume_cell_inside(v, cell)) {
    return false;
  }
  GpuVolumeCell c = volume_fetch_cell(LANTERN_VOLUME_GRID volume_cell_index(v, cell));
  if (c.brick == kVolumeEmptyBrick) {
    return false;
  }
  uvec3 local = uvec3(ijk - vec3(v.cell_origin) - cell * float(kVolumeBrickSize));
  index = c.brick * kVolumeBrickVoxels + volume_brick_offset(local);
  return true;
}

// The grid value of voxel ijk.
LANTERN_FUNC float volume_voxel(LANTERN_VOLUME_GRID_PARAM GpuVolume v, vec3 ijk) {
  uint index;
  return volume_voxel_index(LANTERN_VOLUME_GRID v, ijk, index)
             ? volume_fetch_value(LANTERN_VOLUME_GRID index)
             : 0.0f;
}

// The grid value at index-space point p, trilinear between the eight voxel centres around it
// (centres at integer coordinates, OpenVDB's convention). The cell holding floor(p) is read once
// and all eight values come from its brick (the apron holds the +1 layer). 0 when that cell is
// outside the box: the box covers the support grown by a voxel, so every voxel such a sample
// would read is zero.
LANTERN_FUNC float volume_density_index(LANTERN_VOLUME_GRID_PARAM GpuVolume v, vec3 p) {
  vec3 base = floor(p);
  vec3 f = p - base;
  uint i;
  if (!volume_voxel_index(LANTERN_VOLUME_GRID v, base, i)) {
    return 0.0f;
  }
  const uint dy = kVolumeBrickEdge;
  const uint dz = kVolumeBrickEdge * kVolumeBrickEdge;
  float b000 = volume_fetch_value(LANTERN_VOLUME_GRID i);
  float b100 = volume_fetch_value(LANTERN_VOLUME_GRID i + 1u);
  float b010 = volume_fetch_value(LANTERN_VOLUME_GRID i + dy);
  float b110 = volume_fetch_value(LANTERN_VOLUME_GRID i + dy + 1u);
  float b001 = volume_fetch_value(LANTERN_VOLUME_GRID i + dz);
  float b101 = volume_fetch_value(LANTERN_VOLUME_GRID i + dz + 1u);
  float b011 = volume_fetch_value(LANTERN_VOLUME_GRID i + dz + dy);
  float b111 = volume_fetch_value(LANTERN_VOLUME_GRID i + dz + dy + 1u);
  return mix(mix(mix(b000, b100, f.x), mix(b010, b110, f.x), f.y),
             mix(mix(b001, b101, f.x), mix(b011, b111, f.x), f.y), f.z);
}

// The majorant (scalar, >= every channel of sigma_t) of the cell holding index-space point p;
// 0 outside the grid.
LANTERN_FUNC float volume_majorant_index(LANTERN_VOLUME_GRID_PARAM GpuVolume v, vec3 p) {
  vec3 cell = volume_cell_of(v, p);
  if (!volume_cell_inside(v, cell)) {
    return 0.0f;
  }
  GpuVolumeCell c = volume_fetch_cell(LANTERN_VOLUME_GRID volume_cell_index(v, cell));
  return c.max_density * v.absorption.w;
}

// --- Majorant DDA --------------------------------------------------------------------------------
// The cells a ray (index space; t keeps the caller's units) crosses, front to back, each with the
// parameter interval [t0, t1] it spends inside (Amanatides & Woo 1987).
struct VolumeDda {
  vec4 t_next;   // xyz: t at the next cell boundary per axis; w: t where the walk is now
  vec4 t_delta;  // xyz: t across one cell per axis; w: t where the walk ends
  vec4 cell;     // xyz: the current cell (integer-valued); w: 0
  vec4 step;     // xyz: -1, 0 or +1 per axis; w: 0
};
LANTERN_STATIC_SIZE(VolumeDda, 64);

// Starts the walk over [t_min, t_max]; false when the ray misses the cell box.
LANTERN_FUNC bool volume_dda_begin(GpuVolume v, vec3 origin, vec3 dir, float t_min, float t_max,
                                   LANTERN_OUT(VolumeDda) dda) {
  dda.t_next = vec4(0.0f);
  dda.t_delta = vec4(0.0f);
  dda.cell = vec4(0.0f);
  dda.step = vec4(0.0f);
  vec3 cells = vec3(float(v.cells.x), float(v.cells.y), float(v.cells.z));
  vec3 lo = vec3(v.cell_origin);
  vec3 hi = lo + cells * float(kVolumeBrickSize);
  float t0 = t_min;
  float t1 = t_max;
  if (!ray_box_clip(lo, hi, origin, dir, t0, t1)) {
    return false;
  }
  vec3 cell = clamp(volume_cell_of(v, origin + t0 * dir), vec3(0.0f), cells - vec3(1.0f));
  for (int a = 0; a < 3; ++a) {
    float size = float(kVolumeBrickSize);
    if (abs(dir[a]) < 1e-30f) {
      dda.t_next[a] = kVolumeNoCollision;
      dda.t_delta[a] = kVolumeNoCollision;
    } else if (dir[a] > 0.0f) {
      dda.t_next[a] = (lo[a] + (cell[a] + 1.0f) * size - origin[a]) / dir[a];
      dda.t_delta[a] = size / dir[a];
      dda.step[a] = 1.0f;
    } else {
      dda.t_next[a] = (lo[a] + cell[a] * size - origin[a]) / dir[a];
      dda.t_delta[a] = -size / dir[a];
      dda.step[a] = -1.0f;
    }
  }
  dda.t_next.w = t0;
  dda.t_delta.w = t1;
  dda.cell = vec4(cell, 0.0f);
  return true;
}

// The next cell: its interval [t0, t1] and record. False when the walk is over.
LANTERN_FUNC bool volume_dda_next(LANTERN_VOLUME_GRID_PARAM GpuVolume v,
                                  LANTERN_INOUT(VolumeDda) dda, LANTERN_OUT(float) t0,
                                  LANTERN_OUT(float) t1, LANTERN_OUT(GpuVolumeCell) cell) {
  t0 = dda.t_next.w;
  t1 = t0;
  cell.brick = kVolumeEmptyBrick;
  cell.max_density = 0.0f;
  cell.min_density = 0.0f;
  cell.pad0 = 0u;
  vec3 c = vec3(dda.cell);
  if (!(t0 < dda.t_delta.w) || !volume_cell_inside(v, c)) {
    return false;
  }
  int axis = 0;
  if (dda.t_next.y < dda.t_next[axis]) {
    axis = 1;
  }
  if (dda.t_next.z < dda.t_next[axis]) {
    axis = 2;
  }
  t1 = min(dda.t_next[axis], dda.t_delta.w);
  cell = volume_fetch_cell(LANTERN_VOLUME_GRID volume_cell_index(v, c));
  dda.t_next.w = t1;
  dda.cell[axis] += dda.step[axis];
  dda.t_next[axis] += dda.t_delta[axis];
  return true;
}

// --- Transmittance through the grid -------------------------------------------------------------
// Unbiased estimates of the transmittance along index-space ray origin + t dir over
// [t_min, t_max] (t in the caller's units: world metres when the ray came through
// world_to_index), segment by segment over the majorant cells. `medium` is passed to
// medium_extinction (GLSL: the shader's, e.g. volume `medium`'s extinction at p; C++: the
// VolumeMedium's).

#ifdef __cplusplus
// A grid with its record as a tracking medium (shared/volume.h): sigma_t at index-space p.
struct VolumeMedium {
  VolumeGridView grid;
  GpuVolume volume;
};
inline vec3 medium_extinction(const VolumeMedium& m, uint, vec3 p) {
  return volume_extinction(m.volume, volume_density_index(m.grid, m.volume, p));
}
#define LANTERN_VOLUME_MEDIUM VolumeMedium{grid, v},
#else
#define LANTERN_VOLUME_MEDIUM
#endif

// The walk both estimators share: the majorant cells front to back, one segment estimate each
// (ratio tracking at the cell's majorant, or with `residual` residual ratio tracking with the
// cell's min_density extinction as the control), stopping once every channel is 0.
LANTERN_FUNC vec3 volume_transmittance_walk(LANTERN_VOLUME_GRID_PARAM uint medium, GpuVolume v,
                                            vec3 origin, vec3 dir, float t_min, float t_max,
                                            float roulette, bool residual,
                                            LANTERN_INOUT(uint) rng) {
  vec3 transmittance = vec3(1.0f);
  VolumeDda dda;
  if (!volume_dda_begin(v, origin, dir, t_min, t_max, dda)) {
    return transmittance;
  }
  float t0;
  float t1;
  GpuVolumeCell cell;
  while (volume_dda_next(LANTERN_VOLUME_GRID v, dda, t0, t1, cell)) {
    if (residual) {
      vec3 control = volume_extinction(v, cell.min_density);
      float majorant = (cell.max_density - cell.min_density) * v.absorption.w;
      transmittance *= residual_ratio_tracking(LANTERN_VOLUME_MEDIUM medium, origin, dir, t0, t1,
                                               control, majorant, roulette, rng);
    } else {
      float majorant = cell.max_density * v.absorption.w;
      transmittance *= ratio_tracking(LANTERN_VOLUME_MEDIUM medium, origin, dir, t0, t1, majorant,
                                      roulette, rng);
    }
    if (transmittance.x == 0.0f && transmittance.y == 0.0f && transmittance.z == 0.0f) {
      break;
    }
  }
  return transmittance;
}

// Ratio tracking at each cell's majorant.
LANTERN_FUNC vec3 volume_transmittance_ratio(LANTERN_VOLUME_GRID_PARAM uint medium, GpuVolume v,
                                             vec3 origin, vec3 dir, float t_min, float t_max,
                                             float roulette, LANTERN_INOUT(uint) rng) {
  return volume_transmittance_walk(LANTERN_VOLUME_GRID medium, v, origin, dir, t_min, t_max,
                                   roulette, false, rng);
}

// Residual ratio tracking with each cell's min_density extinction as the control.
LANTERN_FUNC vec3 volume_transmittance_residual(LANTERN_VOLUME_GRID_PARAM uint medium, GpuVolume v,
                                                vec3 origin, vec3 dir, float t_min, float t_max,
                                                float roulette, LANTERN_INOUT(uint) rng) {
  return volume_transmittance_walk(LANTERN_VOLUME_GRID medium, v, origin, dir, t_min, t_max,
                                   roulette, true, rng);
}

LANTERN_END_SHARED

#endif
