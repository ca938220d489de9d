// Participating media as level data (CLI.md "Volume units", docs/levels.md "volumes"): a float
// grid in an OpenVDB file (or one the runtime generates), placed in the world, with its optical
// coefficients. At a point where the grid's value is d the scattering coefficient is
// density_scale * d * scattering and the absorption coefficient density_scale * d * absorption
// (1/m per channel); the phase function is Henyey-Greenstein with `anisotropy` g in (-1, 1).
// The engine reads no .vdb file: runtime/volume/ loads (and generates) the grids.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "engine/scene/behaviour.h"
#include "engine/scene/transform.h"

namespace lantern {

enum class VolumeGeneratorType : std::uint8_t { Constant, SmokePlume, GroundFog };

// The names level files use: "constant", "smoke_plume", "ground_fog" (one table, volume.cpp).
const char* volume_generator_name(VolumeGeneratorType type);
std::optional<VolumeGeneratorType> volume_generator_from_name(std::string_view name);
std::string volume_generator_names();  // "constant, smoke_plume, ground_fog"

// A procedural grid the runtime writes as a real .vdb file (runtime/volume/volume_generator.h)
// before loading it like any other: deterministic given the parameters.
struct VolumeGenerator {
  VolumeGeneratorType type = VolumeGeneratorType::Constant;
  std::uint64_t seed = 1;
  glm::vec3 size{4.0f, 2.0f, 4.0f};  // metres: the box the grid fills, centred on x and z, y from 0
  float voxel_size = 0.1f;           // metres
  bool operator==(const VolumeGenerator&) const = default;

  // Voxels along x, y, z: ceil(size / voxel_size), at least 1.
  glm::uvec3 voxel_counts() const {
    return glm::uvec3(glm::max(glm::ceil(size / voxel_size - 1e-4f), glm::vec3(1.0f)));
  }
};

// Generated grids stay small (levels ship no big files, and generation runs at load time).
inline constexpr std::uint64_t kMaxGeneratedVolumeVoxels = std::uint64_t{1} << 22;

struct Volume {
  std::string name;
  // Exactly one source: a .vdb file (absolute, checked to exist at level load) or a generator.
  std::filesystem::path file;
  std::optional<VolumeGenerator> generator;
  std::string grid = "density";  // the float grid's name in the file
  Transform transform;           // placement, applied after the grid's own index-to-world
  float density_scale = 1.0f;
  glm::vec3 scattering{1.0f};  // per unit density, 1/m
  glm::vec3 absorption{0.0f};  // per unit density, 1/m
  float anisotropy = 0.0f;     // Henyey-Greenstein g, > 0 forward
  std::optional<Behaviour> behaviour;
  // The place errors name: "level.json: /volumes/2" (the grid loader adds the .vdb's own place).
  std::string where;

  // Extinction per unit grid value (1/m): density_scale * (scattering + absorption).
  glm::vec3 extinction_per_density() const { return density_scale * (scattering + absorption); }
};

}  // namespace lantern
