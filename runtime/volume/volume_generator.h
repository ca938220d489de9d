// Procedural volumes written as real OpenVDB files (engine/scene/volume.h VolumeGenerator), so
// levels can use fog and smoke without committed binaries. Deterministic: the same parameters
// give the same voxels on every machine (integer hashing, no std distributions).
//   constant     density 1 in the whole box (homogeneous fog; closed-form tests)
//   smoke_plume  a wobbling column rising from the box's floor centre, widening and thinning
//                with height, modulated by value-noise fbm
//   ground_fog   a bank that thins exponentially with height (scale height = size.y / 3), with
//                fbm and soft horizontal edges
// One float grid named "density" with values in [0, 1], active where > 0; index-to-world puts
// voxel centres on a voxel_size lattice filling the box x, z in [-size/2, size/2], y in
// [0, size.y]. Generated files live in the volume cache, named by a hash of the parameters.
#pragma once

#include <filesystem>

#include "engine/scene/volume.h"

namespace lantern::runtime {

// $LANTERN_CACHE_DIR/volumes if set, else <build dir>/volume-cache.
std::filesystem::path volume_cache_dir();

// "<type>-<16 hex digits of a hash over the parameters and the generator version>.vdb".
std::string generated_volume_name(const VolumeGenerator& generator);

// Writes the grid to `file` (atomically: a temporary file, then a rename).
void write_generated_volume(const VolumeGenerator& generator, const std::filesystem::path& file);

// The cached file for `generator`, written first when absent.
std::filesystem::path generated_volume_file(const VolumeGenerator& generator);

}  // namespace lantern::runtime
