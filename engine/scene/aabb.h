// Axis-aligned bounding box; empty until a point is added.
#pragma once

#include <glm/glm.hpp>
#include <limits>

namespace lantern {

struct Aabb {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};

  bool empty() const { return min.x > max.x; }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Aabb& b) {
    if (b.empty()) return;
    extend(b.min);
    extend(b.max);
  }
  glm::vec3 center() const { return 0.5f * (min + max); }
  glm::vec3 extent() const { return empty() ? glm::vec3(0.0f) : max - min; }
  // The box enclosing this box after an affine transform.
  Aabb transformed(const glm::mat4& m) const {
    Aabb out;
    if (empty()) return out;
    for (int i = 0; i < 8; ++i) {
      glm::vec3 c((i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z);
      out.extend(glm::vec3(m * glm::vec4(c, 1.0f)));
    }
    return out;
  }
};

}  // namespace lantern
