// The "volumes" section of `lantern info` (volume_requirements.h).
#include "lighting/scene/volume_requirements.h"

#include <fmt/format.h>

namespace lantern::lighting {
namespace {

std::string mib(std::uint64_t bytes) {
  return fmt::format("{:.2f} MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
}

}  // namespace

void describe_volumes(const Level& level, const std::vector<runtime::VolumeGrid>& grids,
                      LevelSummary& summary) {
  if (level.volumes.empty()) {
    summary.enabled["volumes"] = {{"structure", "none"},
                                  {"why", "the level has no volumes"},
                                  {"passes", "volume passes: none"},
                                  {"bytes", 0}};
    return;
  }
  nlohmann::json list = nlohmann::json::array();
  std::uint64_t bytes = 0;
  for (std::size_t i = 0; i < grids.size(); ++i) {
    const Volume& v = level.volumes[i];
    const runtime::VolumeGrid& g = grids[i];
    bytes += g.bytes() + sizeof(gpu::GpuVolume);
    list.push_back(
        {{"name", v.name},
         {"file", v.generator ? fmt::format("{} (generated: {})", g.file.filename().string(),
                                            volume_generator_name(v.generator->type))
                              : g.file.filename().string()},
         {"grid", g.grid_name},
         {"active_voxels", g.active_voxels},
         {"dense_voxels", g.dense_voxels()},
         {"bricks", g.brick_count()},
         {"brick_voxels", g.brick_count() * gpu::kVolumeBrickVoxels},
         {"cells", g.cell_count()},
         {"max_value", g.max_value},
         {"bytes", g.bytes() + sizeof(gpu::GpuVolume)}});
  }
  summary.enabled["volumes"] = {
      {"structure",
       "8^3 float bricks of the occupied cells + a majorant grid (max/min grid "
       "value per 8^3 cell), index space per grid"},
      {"why", fmt::format("{} volume{} in the level", grids.size(), grids.size() == 1 ? "" : "s")},
      {"grids", list},
      {"passes",
       "volume passes after the integrator: baseline and reference volume.camera, ReSTIR "
       "volume.restir_initial + volume.restir_spatial (media reservoirs: RIS, temporal and "
       "spatial reuse); both give transmittance along camera rays and single-scattered light "
       "from every light kind (distance sampling MIS'd with equiangular); transmittance on "
       "every shadow ray (residual ratio tracking over the majorant cells)"},
      {"bytes", bytes},
      {"memory", mib(bytes)}};
}

}  // namespace lantern::lighting
