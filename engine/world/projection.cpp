// Vulkan-convention perspective projection (see projection.h).
#include "engine/world/projection.h"

#include <cmath>

namespace lantern {

glm::mat4 vulkan_perspective(float yfov, float aspect, float znear, float zfar) {
  const float f = 1.0f / std::tan(0.5f * yfov);
  glm::mat4 p(0.0f);
  p[0][0] = f / aspect;
  p[1][1] = -f;     // Vulkan's y axis points down
  p[2][3] = -1.0f;  // w = -z_view
  if (zfar > 0.0f) {
    // depth = zfar (d - znear) / (d (zfar - znear)) for view distance d = -z.
    p[2][2] = zfar / (znear - zfar);
    p[3][2] = znear * zfar / (znear - zfar);
  } else {
    // The limit zfar → ∞: depth = 1 - znear / d.
    p[2][2] = -1.0f;
    p[3][2] = -znear;
  }
  return p;
}

}  // namespace lantern
