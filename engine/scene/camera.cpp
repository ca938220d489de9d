// Camera helpers: view matrix and look-at orientation.
#include "engine/scene/camera.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace lantern {

glm::mat4 Camera::view_matrix() const {
  glm::mat4 world = glm::mat4_cast(orientation);
  world[3] = glm::vec4(position, 1.0f);
  return glm::inverse(world);
}

glm::quat look_at_orientation(const glm::vec3& eye, const glm::vec3& target) {
  glm::vec3 f = glm::normalize(target - eye);
  glm::vec3 up(0.0f, 1.0f, 0.0f);
  if (std::abs(glm::dot(f, up)) > 0.999f) up = glm::vec3(0.0f, 0.0f, 1.0f);
  glm::vec3 right = glm::normalize(glm::cross(f, up));
  glm::vec3 true_up = glm::cross(right, f);
  // Columns are the camera's local axes in world space: +X right, +Y up, +Z backwards.
  glm::mat3 basis(right, true_up, -f);
  return glm::normalize(glm::quat_cast(basis));
}

}  // namespace lantern
