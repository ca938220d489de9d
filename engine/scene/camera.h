// A perspective camera as data (glTF conventions: it looks down its local -Z, +Y up).
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace lantern {

struct Camera {
  float yfov = 0.8f;    // vertical field of view, radians
  float aspect = 0.0f;  // width / height; 0 = take it from the output size
  float znear = 0.05f;
  float zfar = 0.0f;  // 0 = infinite far plane
  glm::vec3 position{0.0f};
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};

  glm::vec3 forward() const { return orientation * glm::vec3(0.0f, 0.0f, -1.0f); }
  glm::mat4 view_matrix() const;
};

// The orientation of a camera at `eye` looking at `target` with +Y up (falls back to +Z up when
// looking straight up or down).
glm::quat look_at_orientation(const glm::vec3& eye, const glm::vec3& target);

}  // namespace lantern
