// VolumeGrid: bricks with their aprons, the majorant grid and lookups through the shared code
// (volume_grid.h).
#include "runtime/volume/volume_grid.h"

#include <algorithm>
#include <limits>

namespace lantern::runtime {
namespace {

constexpr int kBrick = static_cast<int>(gpu::kVolumeBrickSize);
// The builder stages each cell's own 8^3 voxels before finish() adds the aprons.
constexpr std::size_t kBlockVoxels = std::size_t{kBrick} * kBrick * kBrick;

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
  blocks_.assign(std::size_t(counts_.x) * counts_.y * counts_.z, gpu::kVolumeEmptyBrick);
}

void VolumeGridBuilder::set(glm::ivec3 ijk, float value) {
  if (value == 0.0f) return;
  value_sum_ += value;
  ++non_zero_;
  const glm::ivec3 rel = ijk - origin_;
  const glm::ivec3 cell = rel / kBrick;  // rel >= 0: the box covers every active voxel
  std::uint32_t& block = blocks_[cell_index(cell)];
  if (block == gpu::kVolumeEmptyBrick) {
    block = static_cast<std::uint32_t>(voxels_.size() / kBlockVoxels);
    voxels_.resize(voxels_.size() + kBlockVoxels, 0.0f);
  }
  const glm::ivec3 local = rel - cell * kBrick;
  voxels_[std::size_t(block) * kBlockVoxels +
          std::size_t(local.x + kBrick * (local.y + kBrick * local.z))] = value;
}

std::size_t VolumeGridBuilder::cell_index(glm::ivec3 c) const {
  return std::size_t(c.x) + counts_.x * (std::size_t(c.y) + counts_.y * std::size_t(c.z));
}

float VolumeGridBuilder::staged(glm::ivec3 rel) const {
  const glm::ivec3 cell = rel / kBrick;  // rel >= 0 here
  if (glm::any(glm::greaterThanEqual(glm::uvec3(cell), counts_))) return 0.0f;
  const std::uint32_t block = blocks_[cell_index(cell)];
  if (block == gpu::kVolumeEmptyBrick) return 0.0f;
  const glm::ivec3 local = rel - cell * kBrick;
  return voxels_[std::size_t(block) * kBlockVoxels +
                 std::size_t(local.x + kBrick * (local.y + kBrick * local.z))];
}

VolumeGrid VolumeGridBuilder::finish(VolumeGrid grid) {
  grid.cell_origin = origin_;
  grid.cell_counts = counts_;
  grid.mean_value = non_zero_ > 0 ? static_cast<float>(value_sum_ / double(non_zero_)) : 0.0f;
  grid.cells.assign(blocks_.size(), gpu::GpuVolumeCell{gpu::kVolumeEmptyBrick, 0.0f, 0.0f, 0u});
  grid.values.clear();
  const int edge = static_cast<int>(gpu::kVolumeBrickEdge);
  std::vector<float> brick(gpu::kVolumeBrickVoxels);
  // Each cell's brick holds the 9^3 voxels a trilinear sample in the cell reads (its own and the
  // first layer of its +x/+y/+z neighbours); the cell's bounds are taken over exactly those.
  // Cells whose 9^3 voxels are all zero keep no brick and max = min = 0.
  for (unsigned z = 0; z < counts_.z; ++z)
    for (unsigned y = 0; y < counts_.y; ++y)
      for (unsigned x = 0; x < counts_.x; ++x) {
        const glm::ivec3 c(x, y, z);
        bool any = false;
        for (int n = 0; n < 8 && !any; ++n) {
          const glm::ivec3 nc = c + glm::ivec3(n & 1, (n >> 1) & 1, (n >> 2) & 1);
          any = glm::all(glm::lessThan(glm::uvec3(nc), counts_)) &&
                blocks_[cell_index(nc)] != gpu::kVolumeEmptyBrick;
        }
        if (!any) continue;
        float hi = 0.0f, lo = std::numeric_limits<float>::max();
        const glm::ivec3 base = c * kBrick;
        for (int k = 0; k < edge; ++k)
          for (int j = 0; j < edge; ++j)
            for (int i = 0; i < edge; ++i) {
              const float v = staged(base + glm::ivec3(i, j, k));
              brick[std::size_t(i + edge * (j + edge * k))] = v;
              hi = std::max(hi, v);
              lo = std::min(lo, v);
            }
        if (hi == 0.0f) continue;
        gpu::GpuVolumeCell& cell = grid.cells[cell_index(c)];
        cell.brick = static_cast<std::uint32_t>(grid.values.size() / gpu::kVolumeBrickVoxels);
        cell.max_density = hi;
        cell.min_density = lo;
        grid.values.insert(grid.values.end(), brick.begin(), brick.end());
      }
  value_sum_ = 0.0;
  non_zero_ = 0;
  counts_ = glm::uvec3(0);
  blocks_.clear();
  voxels_.clear();
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
