// Analytic lights per KHR_lights_punctual, in the units of CLI.md "glTF units": point and spot
// intensity is radiant intensity (W/sr per channel), directional intensity is irradiance (W/m²);
// photometric values are read as radiometric with factor 1.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <optional>
#include <string>

#include "engine/scene/behaviour.h"

namespace lantern {

enum class LightType : std::uint8_t { Point, Spot, Directional };

const char* light_type_name(LightType type);  // "point", "spot", "directional"

struct Light {
  std::string name;
  LightType type = LightType::Point;
  glm::vec3 color{1.0f};                       // linear RGB multiplier
  float intensity = 1.0f;                      // W/sr (point, spot) or W/m² (directional)
  float range = 0.0f;                          // 0 = no range: pure inverse-square falloff
  float inner_cone = 0.0f;                     // spot: radians, < outer_cone
  float outer_cone = glm::pi<float>() / 4.0f;  // spot: radians, <= pi/2
  glm::vec3 position{0.0f};                    // world space (ignored for directional)
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // world; the light shines down its local -Z
  std::optional<Behaviour> behaviour;

  glm::vec3 direction() const { return rotation * glm::vec3(0.0f, 0.0f, -1.0f); }
};

}  // namespace lantern
