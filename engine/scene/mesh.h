// Triangle mesh as plain data: one material per mesh (a glTF primitive becomes one Mesh).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "engine/scene/aabb.h"

namespace lantern {

struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;      // same count as positions
  std::vector<glm::vec2> uvs;          // TEXCOORD_0: same count as positions, or empty
  std::vector<glm::vec2> uvs1;         // TEXCOORD_1 (when a texture samples it), or empty
  // Vertex tangents (glTF TANGENT): xyz the unit object-space direction of increasing u, w = +1
  // or -1 with the normal map's +Y ("up", decreasing v) = w * cross(normal, xyz). Same count as
  // positions, or empty (the lighting module then generates them: engine/scene/mesh_tangents.h).
  std::vector<glm::vec4> tangents;
  std::vector<std::uint32_t> indices;  // triangle list
  Aabb bounds;                         // object space

  std::size_t triangle_count() const { return indices.size() / 3; }
  // The texcoords of set `set` (TextureRef::texcoord: 0 or 1).
  const std::vector<glm::vec2>& texcoords(std::uint32_t set) const { return set == 1 ? uvs1 : uvs; }
};

}  // namespace lantern
