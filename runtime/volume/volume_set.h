// The grids of a level's volumes (Level::volumes), loaded through OpenVDB: a file entry reads its
// .vdb, a generator entry first writes its .vdb into the volume cache (volume_generator.h). A
// level without volumes loads nothing (OpenVDB is not even initialised) and allocates nothing.
// Bad input is an InputError naming the level entry and the file (vdb_reader.h), exit 2.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/scene/level.h"
#include "runtime/volume/volume_grid.h"

namespace lantern::runtime {

// Extinction beyond this (1/m, at the grid's largest value) is refused as absurd: a mean free
// path of a nanometre is a unit mistake, not a medium.
inline constexpr float kMaxVolumeExtinction = 1.0e9f;

// One volume's grid, checked against its coefficients.
VolumeGrid load_volume_grid(const Volume& volume);

// Level::volumes in order; empty (no allocation) for a level without volumes.
std::vector<VolumeGrid> load_volume_grids(const Level& level);

// Grids read from .vdb files by this process so far (tests: a level without volumes reads none).
std::uint64_t volume_grids_read();

// The GPU record of `volume` placed by `placement` (its WorldMatrix this frame) with its cells at
// `first_cell` of a shared cell array.
gpu::GpuVolume volume_record(const Volume& volume, const VolumeGrid& grid,
                             const glm::mat4& placement, std::uint32_t first_cell);

}  // namespace lantern::runtime
