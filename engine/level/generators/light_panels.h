// The light_panels generator: goal 3's light-count scaling level (issue 12). A fixed scene --
// floor, pillars and awning slabs that occlude, and `panels` rectangular ceiling panels facing
// down -- in which only the subdivision of the panels changes: each panel is an nx x ny grid of
// emissive quads that tile it exactly, with the panel's one radiance, so every emitter count
// (`emitter_triangles`, 2 per quad) carries the same total power over the same emitting surface.
// Frame time against emitter count then isolates light sampling from geometry (light_field's
// geometry grows with its emitters). Deterministic given the seed; the layout does not depend on
// the count.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>

#include "engine/level/level_builder.h"

namespace lantern {

struct LightPanelsParams {
  std::uint64_t seed = 1;
  std::uint32_t emitter_triangles = 1000;  // a multiple of 2 x panels
  std::uint32_t panels = 20;
  glm::vec2 panel_size{2.4f, 1.2f};   // metres along x and z
  float extent = 40.0f;               // the floor is extent x extent metres
  std::uint32_t pillars = 36;         // occluders on a jittered grid, 0.8 x 4 x 0.8 m
  std::uint32_t awnings = 16;         // occluding slabs at 2.5..3.5 m, 3 x 0.1 x 1.5 m
  glm::vec2 radiance{20.0f, 200.0f};  // W/(sr·m²), log-uniform per panel
  float height = 5.0f;                // panel height, metres
  std::string path_name = "walk";
  float path_duration = 30.0f;
};

// Quads per panel along x and z for `cells` = emitter_triangles / (2 panels): the divisor pair
// nx * ny = cells whose cells are closest to square on a size.x x size.y panel.
glm::uvec2 light_panel_grid(std::uint32_t cells, glm::vec2 size);

void generate_light_panels(const LightPanelsParams& params, LevelBuilder& builder,
                           const std::string& where);

}  // namespace lantern
