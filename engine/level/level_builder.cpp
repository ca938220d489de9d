// LevelBuilder: validated appends to a Level.
#include "engine/level/level_builder.h"

namespace lantern {

std::uint32_t LevelBuilder::add_material(Material material) {
  level_.materials.push_back(std::move(material));
  return static_cast<std::uint32_t>(level_.materials.size() - 1);
}

std::uint32_t LevelBuilder::add_mesh(Mesh mesh, const std::string& where) {
  finalize_mesh(mesh, where, diagnostics_);
  level_.meshes.push_back(std::move(mesh));
  return static_cast<std::uint32_t>(level_.meshes.size() - 1);
}

void LevelBuilder::add_instance(std::string name, std::uint32_t mesh, std::uint32_t material,
                                const Transform& transform, std::optional<Behaviour> behaviour) {
  Instance inst;
  inst.name = std::move(name);
  inst.mesh = mesh;
  inst.material = material;
  inst.transform = transform;
  inst.world = transform.matrix();
  inst.behaviour = std::move(behaviour);
  level_.instances.push_back(std::move(inst));
}

}  // namespace lantern
