// Entry point for loading levels: resolves a LEVEL argument (CLI.md) to a file and loads a JSON
// level or a bare .gltf/.glb into a plain-data Level. Bad input throws lantern::InputError.
#pragma once

#include <filesystem>
#include <string_view>

#include "engine/scene/level.h"

namespace lantern {

// The content/ directory: $LANTERN_CONTENT_DIR if set, else the source tree's content/.
std::filesystem::path content_dir();

// A path to a .json/.gltf/.glb file, or the name of a level under content/levels/
// ("cornell_lights" -> content/levels/cornell_lights.json).
std::filesystem::path resolve_level_path(std::string_view level_argument);

// Loads a level file. Degenerate triangles are skipped with one warning that counts them.
Level load_level(const std::filesystem::path& file);

// resolve_level_path + load_level.
inline Level load_level_argument(std::string_view level_argument) {
  return load_level(resolve_level_path(level_argument));
}

}  // namespace lantern
