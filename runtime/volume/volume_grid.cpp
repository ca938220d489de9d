// VolumeGrid: bricks, the majorant grid and lookups through the shared code (volume_grid.h).
#include "runtime/volume/volume_grid.h"

#include <algorithm>
#include <limits>

namespace lantern::runtime {
namespace {

constexpr int kBrick = static_cast<int>(gpu::kVolumeBrickSize);

int floor_div(int a, int b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

// First cell and cell count per axis covering the support [lo - 1, hi + 1].
void cell_box(glm::ivec3 lo, glm::ivec3 hi, glm::ivec3& first, glm::ivec3& count) {
  for (int a = 0; a < 3; ++a) {
    first[a] = floor_div(lo[a] - 1, kBrick);
    count[a] = floor_div(hi[a] + 1, kBrick) - first[a] + 1;
  }
}

}  // namespace

std::uint64_t volume_cells_for(glm::ivec3 lo, glm::ivec3 hi) {
  if (glm::any(glm::lessThan(hi, lo))) return 0;
  glm::ivec3 first, count;
  cell_box(lo, hi, first, count);
  return std::uint64_t(count.x) * std::uint64_t(count.y) * std::uint64_t(count.z);
}

std::uint64_t VolumeGrid::dense_voxels() const {
  if (empty()) return 0;
  const glm::i64vec3 d = glm::i64vec3(active_max) - glm::i64vec3(active_min) + std::int64_t{1};
  return static_cast<std::uint64_t>(d.x * d.y * d.z);
}

gpu::GpuVolume VolumeGrid::lookup_record() const {
  gpu::GpuVolume v{};
  v.world_to_index = glm::mat4(1.0f);
  v.index_to_world = glm::mat4(1.0f);
  v.scattering = glm::vec4(1.0f, 1.0f, 1.0f, 0.0f);
  v.absorption = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  v.support_min = glm::vec4(glm::vec3(active_min) - 1.0f, mean_value);
  v.support_max = glm::vec4(glm::vec3(active_max) + 1.0f, 0.0f);
  v.cell_origin = glm::vec4(glm::vec3(cell_origin), 0.0f);
  v.cells = glm::uvec4(cell_counts, 0u);
  return v;
}

float VolumeGrid::voxel(glm::ivec3 ijk) const {
  return gpu::volume_voxel(view(), lookup_record(), glm::vec3(ijk));
}

float VolumeGrid::sample(glm::vec3 p) const {
  return gpu::volume_density_index(view(), lookup_record(), p);
}

VolumeGridBuilder::VolumeGridBuilder(glm::ivec3 active_min, glm::ivec3 active_max) {
  if (glm::any(glm::lessThan(active_max, active_min))) {
    origin_ = glm::ivec3(0);
    counts_ = glm::uvec3(0);
    return;
  }
  glm::ivec3 first, count;
  cell_box(active_min, active_max, first, count);
  origin_ = first * kBrick;
  counts_ = glm::uvec3(count);
  cells_.assign(std::size_t(counts_.x) * counts_.y * counts_.z,
                gpu::GpuVolumeCell{gpu::kVolumeEmptyBrick, 0.0f, 0.0f, 0u});
}

void VolumeGridBuilder::set(glm::ivec3 ijk, float value) {
  if (value == 0.0f) return;
  value_sum_ += value;
  ++non_zero_;
  const glm::ivec3 rel = ijk - origin_;
  const glm::ivec3 cell = rel / kBrick;  // rel >= 0: the box covers every active voxel
  const std::size_t index =
      std::size_t(cell.x) + counts_.x * (std::size_t(cell.y) + counts_.y * std::size_t(cell.z));
  gpu::GpuVolumeCell& c = cells_[index];
  if (c.brick == gpu::kVolumeEmptyBrick) {
    c.brick = static_cast<std::uint32_t>(values_.size() / gpu::kVolumeBrickVoxels);
    values_.resize(values_.size() + gpu::kVolumeBrickVoxels, 0.0f);
  }
  const glm::ivec3 local = rel - cell * kBrick;
  values_[std::size_t(c.brick) * gpu::kVolumeBrickVoxels +
          std::size_t(local.x + kBrick * (local.y + kBrick * local.z))] = value;
}

VolumeGrid VolumeGridBuilder::finish(VolumeGrid grid) {
  grid.cell_origin = origin_;
  grid.cell_counts = counts_;
  grid.cells = std::move(cells_);
  grid.values = std::move(values_);
  grid.mean_value = non_zero_ > 0 ? static_cast<float>(value_sum_ / double(non_zero_)) : 0.0f;
  value_sum_ = 0.0;
  non_zero_ = 0;
  const gpu::VolumeGridView view = grid.view();
  const gpu::GpuVolume record = grid.lookup_record();
  auto has_brick = [&](glm::ivec3 c) {
    if (glm::any(glm::greaterThanEqual(glm::uvec3(c), counts_))) return false;
    return grid.cells[std::size_t(c.x) +
                      counts_.x * (std::size_t(c.y) + counts_.y * std::size_t(c.z))]
               .brick != gpu::kVolumeEmptyBrick;
  };
  // Bounds over the 9^3 voxels a trilinear sample in the cell reads. Cells with no brick in
  // themselves or their +x/+y/+z neighbours read only zeros: max = min = 0 (the default).
  for (unsigned z = 0; z < counts_.z; ++z)
    for (unsigned y = 0; y < counts_.y; ++y)
      for (unsigned x = 0; x < counts_.x; ++x) {
        const glm::ivec3 c(x, y, z);
        bool any = false;
        for (int n = 0; n < 8 && !any; ++n)
          any = has_brick(c + glm::ivec3(n & 1, (n >> 1) & 1, (n >> 2) & 1));
        if (!any) continue;
        float hi = 0.0f, lo = std::numeric_limits<float>::max();
        const glm::ivec3 base = origin_ + c * kBrick;
        for (int k = 0; k <= kBrick; ++k)
          for (int j = 0; j <= kBrick; ++j)
            for (int i = 0; i <= kBrick; ++i) {
              const float v =
                  gpu::volume_voxel(view, record, glm::vec3(base + glm::ivec3(i, j, k)));
              hi = std::max(hi, v);
              lo = std::min(lo, v);
            }
        gpu::GpuVolumeCell& cell =
            grid.cells[std::size_t(x) + counts_.x * (std::size_t(y) + counts_.y * std::size_t(z))];
        cell.max_density = hi;
        cell.min_density = lo;
      }
  counts_ = glm::uvec3(0);
  return grid;
}

std::uint32_t pack_volume_grid(const VolumeGrid& grid, std::vector<gpu::GpuVolumeCell>& cells,
                               std::vector<float>& values) {
  const auto first_cell = static_cast<std::uint32_t>(cells.size());
  const auto first_brick = static_cast<std::uint32_t>(values.size() / gpu::kVolumeBrickVoxels);
  for (gpu::GpuVolumeCell c : grid.cells) {
    if (c.brick != gpu::kVolumeEmptyBrick) c.brick += first_brick;
    cells.push_back(c);
  }
  values.insert(values.end(), grid.values.begin(), grid.values.end());
  return first_cell;
}

}  // namespace lantern::runtime
