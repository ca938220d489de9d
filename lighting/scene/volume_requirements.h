// `lantern info`'s "volumes" section: the level's grids (file, grid, voxel counts, bricks,
// memory) and the volume passes they enable. A level without volumes reads no grid and reports
// "volume passes: none".
#pragma once

#include <vector>

#include "engine/scene/level.h"
#include "engine/scene/level_summary.h"
#include "runtime/volume/volume_grid.h"

namespace lantern::lighting {

// Adds summary.enabled["volumes"] from the level's grids (runtime::load_volume_grids(level)).
void describe_volumes(const Level& level, const std::vector<runtime::VolumeGrid>& grids,
                      LevelSummary& summary);

}  // namespace lantern::lighting
