// visibility_bench's flattened layout: every instance's triangles moved to world space and merged
// into one BLAS under a single identity instance -- the project's own build and traversal without
// the two-level structure, i.e. what flattening the static instances would give (Embree "flat"
// is the same layout traced by Embree). Hits report instance 0.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "engine/scene/level.h"
#include "lighting/bvh/scene_bvh.h"

namespace lantern::lighting::test {

inline SceneBvh flat_scene_bvh(const Level& level) {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
  for (const Instance& inst : level.instances) {
    const Mesh& mesh = level.meshes.at(inst.mesh);
    const auto base = static_cast<std::uint32_t>(positions.size());
    for (const glm::vec3& p : mesh.positions)
      positions.push_back(glm::vec3(inst.world * glm::vec4(p, 1.0f)));
    for (const std::uint32_t i : mesh.indices) indices.push_back(base + i);
  }
  SceneBvh bvh;
  bvh.add_mesh(MeshBvh(positions, indices));
  const BvhInstanceDesc only{0, glm::mat4(1.0f), 0};
  bvh.set_instances(std::span<const BvhInstanceDesc>(&only, 1));
  return bvh;
}

}  // namespace lantern::lighting::test
