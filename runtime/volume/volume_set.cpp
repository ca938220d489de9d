// Level volumes -> grids (volume_set.h).
#include "runtime/volume/volume_set.h"

#include <fmt/format.h>

#include <atomic>

#include "engine/core/error.h"
#include "engine/scene/finite.h"
#include "runtime/volume/vdb_reader.h"
#include "runtime/volume/volume_generator.h"

namespace lantern::runtime {
namespace {

std::atomic<std::uint64_t>& grids_read() {
  static std::atomic<std::uint64_t> count{0};
  return count;
}

float max_component(glm::vec3 v) {
  return std::max(v.x, std::max(v.y, v.z));
}

}  // namespace

std::uint64_t volume_grids_read() {
  return grids_read().load();
}

VolumeGrid load_volume_grid(const Volume& volume) {
  const std::filesystem::path file =
      volume.generator ? generated_volume_file(*volume.generator) : volume.file;
  ++grids_read();
  VolumeGrid grid;
  try {
    grid = read_vdb_grid(file, volume.grid, volume.where);
  } catch (const InputError&) {
    if (!volume.generator) throw;
    // A generated file in the cache that does not read (a write cut short by a full disk or a
    // killed process): ours to replace, so it is written again once, not blamed on the level.
    std::error_code ec;
    std::filesystem::remove(file, ec);
    grid = read_vdb_grid(generated_volume_file(*volume.generator), volume.grid, volume.where);
  }
  const float peak = grid.max_value * max_component(volume.extinction_per_density());
  if (!std::isfinite(peak) || peak > kMaxVolumeExtinction)
    throw InputError(fmt::format(
        "{}: {}: extinction {:.3g} 1/m (density_scale x grid maximum {:.3g} x (scattering + "
        "absorption)) is absurd (limit {:.0g} 1/m)",
        volume.where, file.string(), peak, grid.max_value, kMaxVolumeExtinction));
  return grid;
}

std::vector<VolumeGrid> load_volume_grids(const Level& level) {
  std::vector<VolumeGrid> grids;
  if (level.volumes.empty()) return grids;
  grids.reserve(level.volumes.size());
  for (const Volume& v : level.volumes) grids.push_back(load_volume_grid(v));
  return grids;
}

gpu::GpuVolume volume_record(const Volume& volume, const VolumeGrid& grid,
                             const glm::mat4& placement, std::uint32_t first_cell) {
  gpu::GpuVolume v = grid.lookup_record();
  v.index_to_world = placement * grid.index_to_world;
  v.world_to_index = glm::inverse(v.index_to_world);
  v.motion = glm::mat4(1.0f);
  v.motion_inverse = glm::mat4(1.0f);
  if (!all_finite(v.world_to_index))
    throw InputError(
        fmt::format("{}: the placement makes the grid's transform singular", volume.where));
  const glm::vec3 s = volume.density_scale * volume.scattering;
  const glm::vec3 a = volume.density_scale * volume.absorption;
  v.scattering = glm::vec4(s, volume.anisotropy);
  v.absorption = glm::vec4(a, max_component(s + a));
  v.cells.w = first_cell;
  return v;
}

}  // namespace lantern::runtime
