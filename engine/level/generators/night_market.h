// The night_market generator: rows of market stalls along aisles, strings of small emissive
// lanterns and glowing signs (the emissive triangles), bulbs and counter spot lights (the
// analytic lights, some flickering, some swinging), crates as occluders, carts that move, and a
// looping camera path through the aisles. Deterministic given the seed.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <filesystem>
#include <string>

#include "engine/level/level_builder.h"

namespace lantern {

struct NightMarketParams {
  std::uint64_t seed = 1;
  std::uint32_t stalls = 240;
  std::uint32_t lanterns_per_stall = 24;
  std::uint32_t lantern_subdivisions = 0;      // icosphere level: 20 triangles at 0, x4 per level
  std::uint32_t lights_per_stall = 5;          // one spot over the counter, the rest point bulbs
  std::uint32_t sign_quads = 16;               // emissive quads per stall sign
  // When set: each stall's sign is one panel (the area the quads would cover) whose emission is
  // this image (an emissive texture: a textured light), instead of sign_quads flat quads.
  std::filesystem::path sign_texture;
  std::uint32_t movers = 24;                   // carts orbiting in the aisles; every 4th spins
  float flicker_fraction = 0.3f;               // lights that flicker
  float moving_light_fraction = 0.05f;         // bulbs that swing (orbit a little)
  glm::vec2 lantern_radiance{20.0f, 2000.0f};  // W/(sr·m²), log-uniform
  glm::vec2 light_intensity{0.5f, 8.0f};       // W/sr, log-uniform
  std::string path_name = "flythrough";
  float path_duration = 40.0f;  // seconds for one loop
};

// Appends the market to the builder's level. `where` names the generator in messages.
void generate_night_market(const NightMarketParams& params, LevelBuilder& builder,
                           const std::string& where);

}  // namespace lantern
