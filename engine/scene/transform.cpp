// TRS <-> matrix conversions.
#include "engine/scene/transform.h"

#include <cmath>

namespace lantern {

glm::mat4 Transform::matrix() const {
  glm::mat4 r = glm::mat4_cast(rotation);
  r[0] *= scale.x;
  r[1] *= scale.y;
  r[2] *= scale.z;
  r[3] = glm::vec4(translation, 1.0f);
  return r;
}

Transform Transform::from_matrix(const glm::mat4& m) {
  Transform t;
  t.translation = glm::vec3(m[3]);
  glm::vec3 c0(m[0]), c1(m[1]), c2(m[2]);
  t.scale = {glm::length(c0), glm::length(c1), glm::length(c2)};
  // A mirroring matrix: fold the reflection into the x scale so the rotation stays proper.
  if (glm::dot(glm::cross(c0, c1), c2) < 0.0f) t.scale.x = -t.scale.x;
  glm::mat3 r(t.scale.x != 0.0f ? c0 / t.scale.x : glm::vec3(1, 0, 0),
              t.scale.y != 0.0f ? c1 / t.scale.y : glm::vec3(0, 1, 0),
              t.scale.z != 0.0f ? c2 / t.scale.z : glm::vec3(0, 0, 1));
  t.rotation = glm::normalize(glm::quat_cast(r));
  return t;
}

}  // namespace lantern
