// The one axis-aligned bounding box: mesh bounds in the engine, BVH build and refit in lighting
// (the GPU node keeps the same min/max corners in shaders/shared/bvh.h). Empty until a point is
// added; the empty box's corners are +-FLT_MAX (finite: arithmetic on it stays NaN-free, and
// growing by it changes nothing).
#pragma once

#include <glm/glm.hpp>
#include <limits>

namespace lantern {

struct Aabb {
  glm::vec3 min{std::numeric_limits<float>::max()};
  glm::vec3 max{-std::numeric_limits<float>::max()};

  bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  void grow(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void grow(const Aabb& b) {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }
  glm::vec3 centroid() const { return 0.5f * (min + max); }
  glm::vec3 extent() const { return empty() ? glm::vec3(0.0f) : max - min; }
  // Surface area; 0 for an empty box.
  float area() const {
    const glm::vec3 e = extent();
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
  // The box enclosing this box after an affine transform (of its 8 transformed corners).
  Aabb transformed(const glm::mat4& m) const {
    Aabb out;
    if (empty()) return out;
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? max.x : min.x, (corner & 2) ? max.y : min.y,
                        (corner & 4) ? max.z : min.z);
      out.grow(glm::vec3(m * glm::vec4(p, 1.0f)));
    }
    return out;
  }
};

}  // namespace lantern
