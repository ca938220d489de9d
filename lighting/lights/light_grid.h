// The light grid (shaders/shared/light_grid.h): the lights binned into world-space cells (a dense
// table of cells over the lights' bounds, each cell's lights in one list) and per light its cell
// and that cell's light count, so the density of a draw near a point is known for any light.
// Built on the CPU from a frame's light list; restir.initial's grid candidates draw from it.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "shared/light_grid.h"
#include "shared/lights.h"

namespace lantern::lighting {

class LightGrid {
 public:
  // Mean lights per occupied cell the cell size aims at (light_grid.cpp picks the edge).
  static constexpr double kTargetLightsPerCell = 32.0;

  LightGrid() = default;
  // Bins `lights` (indices into that list), each cell weighed by the sum of its lights' `powers`
  // (one per light: LightTable::powers()). A list without a placed light (none, or directional
  // only) gives an empty grid (origin_cell.w = 0: nothing is ever drawn from it). The cell edge
  // is the smallest the axes and kLightGridMaxCells allow, else about the one whose occupied
  // cells hold kTargetLightsPerCell lights each.
  LightGrid(std::span<const gpu::GpuLight> lights, std::span<const float> powers);

  const gpu::GpuLightGrid& header() const { return header_; }
  // The dense table (x fastest), each cell's range in the cell-ordered light list and its power.
  std::size_t cell_count() const { return cell_count_; }
  gpu::GpuLightGridCell cell(std::size_t i) const;
  // The k-th slot of the cell-ordered list: its light and its cell's alias table's slot.
  gpu::GpuLightGridEntry entry(std::size_t k) const;
  // Per light of the list: (its cell's key or kLightGridNoCell, the float bits of its share of
  // its cell's alias weights: the probability that a draw from that cell gives it).
  const std::vector<gpu::uvec2>& light_cells() const { return light_cells_; }
  std::uint32_t occupied_cells() const { return occupied_; }
  // The GPU's scene.light_grid: the header's 8 words, the cells' (first, count, power) words, then
  // the cell-ordered list's (light, threshold, alias) words (shared/light_grid.h).
  const std::vector<std::uint32_t>& gpu_words() const { return words_; }

 private:
  gpu::GpuLightGrid header_{};
  std::size_t cell_count_ = 0;
  std::vector<std::uint32_t> words_;
  std::vector<gpu::uvec2> light_cells_;
  std::uint32_t occupied_ = 0;
};

// Where the grid places a light: a triangle's centroid, a point or spot light's position; false
// for a directional light (no place).
bool light_grid_place(const gpu::GpuLight& light, gpu::vec3& place);

}  // namespace lantern::lighting
