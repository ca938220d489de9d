// Appending content to a Level with the checks every loader and generator needs: meshes are
// validated (finalize_mesh) and instances get both TRS and matrix.
#pragma once

#include <optional>
#include <string>

#include "engine/level/mesh_validation.h"
#include "engine/scene/level.h"

namespace lantern {

class LevelBuilder {
 public:
  LevelBuilder(Level& level, LoadDiagnostics& diagnostics)
      : level_(level), diagnostics_(diagnostics) {}

  std::uint32_t add_material(Material material);
  // Validates the mesh (errors prefixed by `where`) and stores it.
  std::uint32_t add_mesh(Mesh mesh, const std::string& where);
  void add_instance(std::string name, std::uint32_t mesh, std::uint32_t material,
                    const Transform& transform, std::optional<Behaviour> behaviour = std::nullopt);
  void add_light(Light light) { level_.lights.push_back(std::move(light)); }

  Level& level() { return level_; }
  LoadDiagnostics& diagnostics() { return diagnostics_; }

 private:
  Level& level_;
  LoadDiagnostics& diagnostics_;
};

}  // namespace lantern
