// The light_field generator: the many-emitter scaling stress. `emitters` small emissive quads
// (2 triangles each) hover over a floor between pillars that occlude them, in a few colours with
// log-uniform radiance, plus a looping camera path over the field. The emitter count is the knob
// (10^3 .. 2·10^6 triangles); everything else stays the same so frame time vs emitters is a
// clean scaling curve. Deterministic given the seed.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>

#include "engine/level/level_builder.h"

namespace lantern {

struct LightFieldParams {
  std::uint64_t seed = 1;
  std::uint32_t emitter_triangles = 1000000;   // rounded up to an even count (quads)
  float extent = 60.0f;                        // the field is extent x extent metres
  std::uint32_t pillars = 64;                  // occluding pillars on a jittered grid
  glm::vec2 radiance{5.0f, 500.0f};            // W/(sr·m²), log-uniform per colour group
  float quad_size = 0.12f;                     // emitter edge length, metres
  std::string path_name = "flyover";
  float path_duration = 30.0f;
};

void generate_light_field(const LightFieldParams& params, LevelBuilder& builder,
                          const std::string& where);

}  // namespace lantern
