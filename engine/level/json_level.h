// Reads a JSON level file (format: docs/levels.md) into a Level, importing the glTF assets it
// places and running its generators.
#pragma once

#include <filesystem>

#include "engine/level/mesh_validation.h"
#include "engine/scene/level.h"

namespace lantern {

void read_json_level(const std::filesystem::path& file, Level& level, LoadDiagnostics& diagnostics);

}  // namespace lantern
