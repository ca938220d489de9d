// light_field: emissive quads in a few material groups (one merged mesh each), pillars, floor.
#include "engine/level/generators/light_field.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/level/generators/generator.h"
#include "engine/level/generators/split_mix.h"
#include "engine/level/primitives.h"

namespace lantern {
namespace {

// Colour groups: one material (and one merged mesh) each; radiance spread over the groups.
constexpr std::array<glm::vec3, 8> kColors = {{{1.00f, 0.55f, 0.25f},
                                               {0.35f, 0.60f, 1.00f},
                                               {1.00f, 0.30f, 0.45f},
                                               {0.45f, 1.00f, 0.55f},
                                               {1.00f, 0.90f, 0.60f},
                                               {0.70f, 0.40f, 1.00f},
                                               {0.30f, 1.00f, 0.95f},
                                               {1.00f, 1.00f, 1.00f}}};

// A random unit vector in the lower hemisphere tilted towards -Y (emitters face the floor).
glm::vec3 downward_normal(SplitMix& rng) {
  const float cos_theta = rng.uniform(0.3f, 1.0f);
  const float sin_theta = std::sqrt(1.0f - cos_theta * cos_theta);
  const float phi = rng.uniform(0.0f, glm::two_pi<float>());
  return {sin_theta * std::cos(phi), -cos_theta, sin_theta * std::sin(phi)};
}

}  // namespace

void generate_light_field(const LightFieldParams& p, LevelBuilder& builder,
                          const std::string& where) {
  SplitMix rng(p.seed ^ 0x6C6967687466ull);  // "lightf"
  const float half = 0.5f * p.extent;
  const std::uint32_t quads = (p.emitter_triangles + 1) / 2;

  std::array<Mesh, kColors.size()> groups;
  for (Mesh& m : groups) {
    m.positions.reserve(4ull * quads / kColors.size() + 4);
    m.normals.reserve(4ull * quads / kColors.size() + 4);
    m.indices.reserve(6ull * quads / kColors.size() + 6);
  }
  for (std::uint32_t q = 0; q < quads; ++q) {
    Mesh& m = groups[rng.below(static_cast<std::uint32_t>(kColors.size()))];
    const glm::vec3 c(rng.uniform(-half, half), rng.uniform(1.5f, 6.0f), rng.uniform(-half, half));
    const glm::vec3 n = downward_normal(rng);
    glm::vec3 t = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0)
                                                                    : glm::vec3(0, 0, 1)));
    const glm::vec3 b = glm::cross(n, t);  // (t, b, n) right-handed: CCW seen from the front
    t *= 0.5f * p.quad_size;
    const glm::vec3 bb = b * (0.5f * p.quad_size);
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (const glm::vec3& corner : {c - t - bb, c + t - bb, c + t + bb, c - t + bb}) {
      m.positions.push_back(corner);
      m.normals.push_back(n);
    }
    for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
  }
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (groups[g].indices.empty()) continue;
    const float t = static_cast<float>(g) / static_cast<float>(groups.size() - 1);
    Material e = generated_emitter(fmt::format("field_emitter_{}", g), kColors[g],
                                   p.radiance.x * std::pow(p.radiance.y / p.radiance.x, t));
    groups[g].name = e.name;
    const std::uint32_t mat = builder.add_material(e);
    const std::uint32_t mesh =
        builder.add_mesh(std::move(groups[g]), fmt::format("{}: emitters {}", where, g));
    builder.add_instance(e.name, mesh, mat, Transform{});
  }

  // Pillars on a jittered grid: occluders for shadow rays.
  if (p.pillars > 0) {
    Mesh pillars;
    const Mesh box = make_box(glm::vec3(1.0f));
    const auto side = static_cast<std::uint32_t>(std::ceil(std::sqrt(double(p.pillars))));
    const float pitch = p.extent / static_cast<float>(side);
    for (std::uint32_t i = 0; i < p.pillars; ++i) {
      const glm::vec3 c((static_cast<float>(i % side) + 0.5f) * pitch - half +
                            rng.uniform(-0.2f, 0.2f) * pitch,
                        4.0f,
                        (static_cast<float>(i / side) + 0.5f) * pitch - half +
                            rng.uniform(-0.2f, 0.2f) * pitch);
      append_transformed(pillars, box,
                         glm::scale(glm::translate(glm::mat4(1.0f), c), {0.8f, 8.0f, 0.8f}));
    }
    pillars.name = "field_pillars";
    const std::uint32_t mat =
        builder.add_material(generated_surface("field_stone", {0.5f, 0.48f, 0.45f}, 0.8f));
    builder.add_instance("field_pillars",
                         builder.add_mesh(std::move(pillars), where + ": pillars"), mat,
                         Transform{});
  }
  const std::uint32_t floor_mat =
      builder.add_material(generated_surface("field_floor", {0.35f, 0.35f, 0.37f}, 0.6f));
  builder.add_instance("field_floor",
                       builder.add_mesh(make_plane(glm::vec2(p.extent + 10.0f)), where + ": floor"),
                       floor_mat, Transform{});

  // A loop around the field at pillar-top height, looking towards the centre.
  constexpr int kSteps = 12;
  add_generated_camera_loop(builder.level(), p.path_name, p.path_duration, kSteps, [&](int i) {
    const float a = glm::two_pi<float>() * static_cast<float>(i) / kSteps;
    return LoopPose{
        {0.55f * half * std::cos(a), 2.5f + 0.8f * std::sin(2.0f * a), 0.55f * half * std::sin(a)},
        {0.0f, 1.0f, 0.0f}};
  });
}

}  // namespace lantern
