// `lantern info`'s "volumes" section: the level's grids (file, grid, voxel counts, bricks,
// memory) and the volume passes they enable. A level without volumes reads no grid and reports
// "volume passes: none".
#pragma once

#include "engine/scene/level.h"
#include "engine/scene/level_summary.h"

namespace lantern::lighting {

// Adds summary.enabled["volumes"]; loads every grid (InputError on bad volume input).
void describe_volumes(const Level& level, LevelSummary& summary);

}  // namespace lantern::lighting
