// A float grid loaded from OpenVDB, in the layout the GPU uploads (shaders/shared/volume_grid.h):
//
// - Index space is the grid's own: voxel (i, j, k) has its centre at integer coordinates; values
//   are trilinear between centres and zero outside the active region (inactive voxels, tiles and
//   everything outside the tree read as 0, whatever the file's background value).
// - The active voxel box [active_min, active_max] (inclusive) grown by one voxel on each side is
//   the support (trilinear interpolation reaches one voxel out). It is covered by a box of
//   cells_x * cells_y * cells_z cells of 8^3 voxels, aligned to multiples of 8 in index space
//   (OpenVDB's leaf nodes); cell (0,0,0) starts at voxel cell_origin; cells are stored x fastest.
// - Each cell holds one brick of 9^3 values (x fastest, then y, z) in `values`: its own 8^3
//   voxels and an apron, the first layer of its +x, +y, +z neighbours, so a trilinear sample in
//   the cell reads one brick. A cell whose 9^3 voxels are all zero has no brick
//   (kVolumeEmptyBrick): memory follows the occupied space.
// - The majorant grid is the cells' max_density (and min_density): bounds of the grid value
//   over the brick, everything a trilinear sample inside the cell reads, so max_density * (max
//   channel of sigma_t per unit value) bounds sigma_t.
// - index_to_world is the grid's affine transform (non-affine grids are refused at load).
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "shared/volume_grid.h"

namespace lantern::runtime {

struct VolumeGrid {
  std::filesystem::path file;
  std::string grid_name;
  glm::mat4 index_to_world{1.0f};
  glm::ivec3 active_min{0};  // inclusive; active_max < active_min when nothing is active
  glm::ivec3 active_max{-1};
  std::uint64_t active_voxels = 0;  // OpenVDB's count (voxels and tiles)
  float max_value = 0.0f;           // over active voxels (>= 0)
  float mean_value = 0.0f;          // over the non-zero voxels (the scattering-distance guide)
  glm::ivec3 cell_origin{0};
  glm::uvec3 cell_counts{0};
  std::vector<gpu::GpuVolumeCell> cells;  // brick indices into this grid's `values`
  std::vector<float> values;              // bricks * kVolumeBrickVoxels

  bool empty() const { return active_voxels == 0; }
  std::uint64_t cell_count() const {
    return std::uint64_t{cell_counts.x} * cell_counts.y * cell_counts.z;
  }
  std::uint64_t brick_count() const { return values.size() / gpu::kVolumeBrickVoxels; }
  // Voxels of the active box, as a dense array would store them.
  std::uint64_t dense_voxels() const;
  std::uint64_t bytes() const {
    return cells.size() * sizeof(gpu::GpuVolumeCell) + values.size() * sizeof(float);
  }

  gpu::VolumeGridView view() const { return {cells.data(), values.data()}; }
  // A record for the shared lookups in index space (identity placement, unit coefficients);
  // volume_record (volume_set.h) makes the full one.
  gpu::GpuVolume lookup_record() const;

  // The value of voxel ijk and the trilinear value at index-space point p (shared code).
  float voxel(glm::ivec3 ijk) const;
  float sample(glm::vec3 index_position) const;
};

// Builds cells and bricks from voxel values: `fill` is called once, with a writer
// set(ijk, value) for every non-zero active voxel, after the active box is known. The values
// must be finite and >= 0 (the reader checks them first). Used by the OpenVDB reader and tests.
class VolumeGridBuilder {
 public:
  VolumeGridBuilder(glm::ivec3 active_min, glm::ivec3 active_max);
  void set(glm::ivec3 ijk, float value);
  // Computes the majorant grid and the mean non-zero value; leaves the builder empty.
  VolumeGrid finish(VolumeGrid header);

 private:
  std::size_t cell_index(glm::ivec3 cell) const;
  // A staged voxel by its index relative to origin_ (>= 0): 0 outside the box or a block.
  float staged(glm::ivec3 rel) const;

  glm::ivec3 origin_;
  glm::uvec3 counts_;
  std::vector<std::uint32_t> blocks_;  // per cell: its staged 8^3 block, or kVolumeEmptyBrick
  std::vector<float> voxels_;          // blocks * 512, x fastest
  double value_sum_ = 0.0;
  std::uint64_t non_zero_ = 0;
};

// Appends the grid's cells and brick values to arrays several volumes share (the GPU's cell and
// value buffers), rebasing its brick indices to the values already there; returns the grid's
// first cell (GpuVolume.cells.w, volume_record's first_cell).
std::uint32_t pack_volume_grid(const VolumeGrid& grid, std::vector<gpu::GpuVolumeCell>& cells,
                               std::vector<float>& values);

// Cells a grid with active box [lo, hi] needs (its support in 8^3 cells); for the voxel cap.
std::uint64_t volume_cells_for(glm::ivec3 lo, glm::ivec3 hi);

}  // namespace lantern::runtime
