// Reading one float grid of an OpenVDB file (.vdb) into a VolumeGrid (volume_grid.h). The only
// place that reads OpenVDB files. Bad input is one InputError "<where>: <file>: <problem>":
// a missing, truncated or corrupt file, a grid name the file lacks (the message lists the grids
// it has), a grid that is not float, a non-affine (e.g. frustum) transform, NaN/Inf or negative
// values (naming the voxel), or more voxels than the caps below.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "runtime/volume/volume_grid.h"

namespace lantern::runtime {

// Registers OpenVDB's grid types, once per process (the reader and the generator both need it).
void initialize_openvdb();

// Caps that keep one grid within a device storage binding (lavapipe: 128 MiB per binding, see
// PLATFORM.md): active voxels (tiles counted by the voxels they cover), and cells of the
// active box (16 bytes each, empty or not).
inline constexpr std::uint64_t kMaxVolumeActiveVoxels = std::uint64_t{1} << 25;
inline constexpr std::uint64_t kMaxVolumeCells = std::uint64_t{1} << 22;

VolumeGrid read_vdb_grid(const std::filesystem::path& file, const std::string& grid_name,
                         const std::string& where);

}  // namespace lantern::runtime
