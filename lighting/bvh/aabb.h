// Axis-aligned bounding box used while building and refitting BVHs (CPU only; the GPU node keeps
// the same min/max corners in shaders/shared/bvh.h).
#pragma once

#include <glm/glm.hpp>
#include <limits>

namespace lantern::lighting {

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
  glm::vec3 extent() const { return max - min; }
  glm::vec3 centroid() const { return 0.5f * (min + max); }
  // Surface area; 0 for an empty box.
  float area() const {
    if (empty()) return 0.0f;
    glm::vec3 e = extent();
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
};

// World-space box of `box` moved by an affine transform (the box of its 8 transformed corners).
inline Aabb transform_aabb(const glm::mat4& m, const Aabb& box) {
  Aabb out;
  if (box.empty()) return out;
  for (int corner = 0; corner < 8; ++corner) {
    glm::vec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                (corner & 4) ? box.max.z : box.min.z);
    out.grow(glm::vec3(m * glm::vec4(p, 1.0f)));
  }
  return out;
}

}  // namespace lantern::lighting
