// light_panels: subdivided emissive ceiling panels over a fixed occluded floor.
#include "engine/level/generators/light_panels.h"

#include <fmt/format.h>

#include <cmath>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "engine/core/error.h"
#include "engine/level/generators/generator.h"
#include "engine/level/generators/split_mix.h"
#include "engine/level/primitives.h"

namespace lantern {
namespace {

// A mesh of boxes of `size` at `centres`, one instance.
void add_boxes(LevelBuilder& builder, const std::string& name, const std::string& where,
               glm::vec3 size, const std::vector<glm::vec3>& centres, glm::vec3 color) {
  if (centres.empty()) return;
  Mesh boxes;
  const Mesh box = make_box(size);
  for (const glm::vec3& c : centres)
    append_transformed(boxes, box, glm::translate(glm::mat4(1.0f), c));
  boxes.name = name;
  const std::uint32_t mat = builder.add_material(generated_surface(name, color, 0.8f));
  builder.add_instance(name, builder.add_mesh(std::move(boxes), where + ": " + name), mat,
                       Transform{});
}

}  // namespace

glm::uvec2 light_panel_grid(std::uint32_t cells, glm::vec2 size) {
  glm::uvec2 best(cells, 1u);
  float best_error = INFINITY;
  for (std::uint32_t nx = 1; nx <= cells; ++nx) {
    if (cells % nx != 0) continue;
    const std::uint32_t ny = cells / nx;
    // Cell aspect (size.x / nx) / (size.y / ny); 0 in log = square.
    const float error =
        std::abs(std::log((size.x * static_cast<float>(ny)) / (size.y * static_cast<float>(nx))));
    if (error < best_error) best_error = error, best = glm::uvec2(nx, ny);
  }
  return best;
}

void generate_light_panels(const LightPanelsParams& p, LevelBuilder& builder,
                           const std::string& where) {
  if (p.panels == 0 || p.emitter_triangles % (2 * p.panels) != 0)
    throw InputError(
        fmt::format("{}: emitter_triangles {} must be a positive multiple of 2 x panels = {}",
                    where, p.emitter_triangles, 2 * p.panels));
  SplitMix rng(p.seed ^ 0x70616e656c73ull);  // "panels"
  const float half = 0.5f * p.extent;
  const glm::uvec2 grid = light_panel_grid(p.emitter_triangles / (2 * p.panels), p.panel_size);

  // Panels on a jittered grid over the middle 70% of the floor, facing down (-y).
  const auto side = static_cast<std::uint32_t>(std::ceil(std::sqrt(double(p.panels))));
  const float pitch = 0.7f * p.extent / static_cast<float>(side);
  for (std::uint32_t i = 0; i < p.panels; ++i) {
    const glm::vec3 centre((static_cast<float>(i % side) + 0.5f) * pitch - 0.35f * p.extent +
                               rng.uniform(-0.15f, 0.15f) * pitch,
                           p.height + rng.uniform(-0.5f, 0.5f),
                           (static_cast<float>(i / side) + 0.5f) * pitch - 0.35f * p.extent +
                               rng.uniform(-0.15f, 0.15f) * pitch);
    const float radiance = p.radiance.x * std::pow(p.radiance.y / p.radiance.x, rng.uniform());
    const glm::vec3 color(rng.uniform(0.6f, 1.0f), rng.uniform(0.6f, 1.0f),
                          rng.uniform(0.6f, 1.0f));
    EmissiveQuadGrid g;
    const glm::vec2 cell = p.panel_size / glm::vec2(grid);
    g.origin = centre - glm::vec3(0.5f * p.panel_size.x, 0.0f, 0.5f * p.panel_size.y);
    g.u = glm::vec3(cell.x, 0.0f, 0.0f);
    g.v = glm::vec3(0.0f, 0.0f, cell.y);  // cross(u, v) = -y: the quads face the floor
    g.nx = grid.x;
    g.ny = grid.y;
    g.size = cell;  // quads tile the panel exactly
    g.color = color;
    g.radiance_min = g.radiance_max = radiance;
    g.pattern = "uniform";
    g.levels = 1;
    for (EmissiveQuadBin& bin : make_emissive_quad_grid(g)) {
      Material e = generated_emitter(fmt::format("panel_{}", i), color, bin.radiance);
      bin.mesh.name = e.name;
      const std::uint32_t mat = builder.add_material(e);
      builder.add_instance(
          e.name, builder.add_mesh(std::move(bin.mesh), fmt::format("{}: panel {}", where, i)), mat,
          Transform{});
    }
  }

  // Occluders: pillars on a jittered grid, awning slabs between the panels and the floor.
  std::vector<glm::vec3> pillars, awnings;
  const auto pillar_side = static_cast<std::uint32_t>(std::ceil(std::sqrt(double(p.pillars))));
  const float pillar_pitch = p.extent / static_cast<float>(std::max(pillar_side, 1u));
  for (std::uint32_t i = 0; i < p.pillars; ++i)
    pillars.push_back({(static_cast<float>(i % pillar_side) + 0.5f) * pillar_pitch - half +
                           rng.uniform(-0.2f, 0.2f) * pillar_pitch,
                       2.0f,
                       (static_cast<float>(i / pillar_side) + 0.5f) * pillar_pitch - half +
                           rng.uniform(-0.2f, 0.2f) * pillar_pitch});
  for (std::uint32_t i = 0; i < p.awnings; ++i)
    awnings.push_back({rng.uniform(-0.4f, 0.4f) * p.extent, rng.uniform(2.5f, 3.5f),
                       rng.uniform(-0.4f, 0.4f) * p.extent});
  add_boxes(builder, "panel_pillars", where, {0.8f, 4.0f, 0.8f}, pillars, {0.5f, 0.48f, 0.45f});
  add_boxes(builder, "panel_awnings", where, {3.0f, 0.1f, 1.5f}, awnings, {0.6f, 0.3f, 0.2f});
  const std::uint32_t floor_mat =
      builder.add_material(generated_surface("panel_floor", {0.35f, 0.35f, 0.37f}, 0.6f));
  builder.add_instance("panel_floor",
                       builder.add_mesh(make_plane(glm::vec2(p.extent)), where + ": floor"),
                       floor_mat, Transform{});

  // A slow walk around the field at eye height, looking towards the centre.
  constexpr int kSteps = 12;
  add_generated_camera_loop(builder.level(), p.path_name, p.path_duration, kSteps, [&](int i) {
    const float a = glm::two_pi<float>() * static_cast<float>(i) / kSteps;
    return LoopPose{{0.45f * half * std::cos(a), 1.7f, 0.45f * half * std::sin(a)},
                    {0.0f, 2.5f, 0.0f}};
  });
}

}  // namespace lantern
