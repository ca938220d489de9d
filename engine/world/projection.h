// Camera matrices in the conventions of frame_snapshot.h (Vulkan clip: y down, depth 0..1).
#pragma once

#include <glm/glm.hpp>

#include "engine/scene/camera.h"

namespace lantern {

// Perspective projection, right-handed view space (looking down -Z) to Vulkan clip space:
// y down, depth 0 at `znear`, 1 at `zfar`; `zfar` = 0 gives an infinite far plane.
glm::mat4 vulkan_perspective(float yfov, float aspect, float znear, float zfar);

}  // namespace lantern
