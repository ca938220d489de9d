// A placement in space as translation, rotation and scale (TRS), with the matrix it stands for.
// Shared by level data and, later, the ECS Transform component.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace lantern {

struct Transform {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
  glm::vec3 scale{1.0f};

  // T * R * S, column vectors (glTF convention).
  glm::mat4 matrix() const;
  // Decomposes an affine matrix into TRS (shear, if any, is dropped; use the matrix for exactness).
  static Transform from_matrix(const glm::mat4& m);

  bool operator==(const Transform&) const = default;
};

}  // namespace lantern
