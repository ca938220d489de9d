// night_market: procedural stalls, lanterns, lights, occluders, movers and a camera path.
// Static pieces are merged into one mesh per material to keep the instance count small.
#include "engine/level/generators/night_market.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <map>

#include "engine/level/generators/generator.h"
#include "engine/level/generators/split_mix.h"
#include "engine/level/primitives.h"

namespace lantern {
namespace {

constexpr float kPitchX = 4.0f;  // stall width + gap
constexpr float kPitchZ = 7.0f;  // stall depth + aisle
constexpr int kPalette = 6;
constexpr int kRadianceBins = 4;

const std::array<glm::vec3, kPalette> kCanvas = {{{0.62f, 0.12f, 0.10f},
                                                  {0.10f, 0.30f, 0.55f},
                                                  {0.70f, 0.55f, 0.12f},
                                                  {0.15f, 0.45f, 0.20f},
                                                  {0.55f, 0.25f, 0.50f},
                                                  {0.75f, 0.72f, 0.65f}}};
const std::array<glm::vec3, kPalette> kGlow = {{{1.00f, 0.55f, 0.20f},
                                                {1.00f, 0.30f, 0.15f},
                                                {1.00f, 0.80f, 0.45f},
                                                {0.95f, 0.40f, 0.60f},
                                                {0.50f, 0.80f, 1.00f},
                                                {1.00f, 0.90f, 0.70f}}};

float log_uniform(SplitMix& rng, glm::vec2 range) {
  if (range.x <= 0.0f || range.y <= range.x) return rng.uniform(range.x, range.y);
  return range.x * std::pow(range.y / range.x, rng.uniform());
}

glm::mat4 box_at(const glm::mat4& frame, glm::vec3 center, glm::vec3 size) {
  return glm::scale(glm::translate(frame, center), size);
}

// Merged static geometry, keyed by material name; materials are created on first use.
struct MergedMeshes {
  std::map<std::string, std::pair<Material, Mesh>> parts;
  void add(const Material& material, const Mesh& piece, const glm::mat4& m) {
    auto [it, inserted] = parts.try_emplace(material.name, material, Mesh{});
    append_transformed(it->second.second, piece, m);
  }
};

}  // namespace

void generate_night_market(const NightMarketParams& p, LevelBuilder& builder,
                           const std::string& where) {
  SplitMix rng(p.seed ^ 0x6E696768746D6B74ull);  // "nightmkt"
  const auto cols =
      static_cast<std::uint32_t>(std::ceil(std::sqrt(static_cast<double>(p.stalls) * 1.5)));
  const std::uint32_t rows = (p.stalls + cols - 1) / cols;
  const float half_w = 0.5f * static_cast<float>(cols - 1) * kPitchX;
  const float half_d = 0.5f * static_cast<float>(rows - 1) * kPitchZ;

  const Mesh unit_box = make_box(glm::vec3(1.0f));
  const Mesh lantern = make_ico_sphere(0.08f, p.lantern_subdivisions);
  Mesh sign_quad = make_plane(glm::vec2(1.0f));  // faces +Y; rotated to face the aisle
  // The textured sign panel: a unit quad facing +Z, image x along +X, image y downwards.
  Mesh sign_panel;
  sign_panel.name = "sign_panel";
  sign_panel.positions = {{-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, 0.0f}, {0.5f, 0.5f, 0.0f}, {-0.5f, 0.5f, 0.0f}};
  sign_panel.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
  sign_panel.uvs = {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}};
  sign_panel.indices = {0, 1, 2, 0, 2, 3};
  std::int32_t sign_image = -1;
  if (!p.sign_texture.empty()) {
    ImageRef ref;
    ref.path = p.sign_texture;
    ref.name = p.sign_texture.filename().string();
    builder.level().images.push_back(std::move(ref));
    sign_image = static_cast<std::int32_t>(builder.level().images.size() - 1);
  }
  MergedMeshes merged;
  const Material wood = generated_surface("market_wood", {0.35f, 0.22f, 0.12f}, 0.7f);
  const Material metal = [] {
    Material m = generated_surface("market_metal", {0.55f, 0.55f, 0.58f}, 0.35f);
    m.metallic = 1.0f;
    return m;
  }();
  const Material crate = generated_surface("market_crate", {0.45f, 0.33f, 0.2f}, 0.8f);
  const Material goods = generated_surface("market_goods", {0.6f, 0.5f, 0.35f}, 0.6f);

  for (std::uint32_t s = 0; s < p.stalls; ++s) {
    const std::uint32_t col = s % cols, row = s / cols;
    const glm::vec3 center(static_cast<float>(col) * kPitchX - half_w, 0.0f,
                           static_cast<float>(row) * kPitchZ - half_d);
    // Even rows face +Z, odd rows -Z: pairs of rows face each other across an aisle.
    const glm::mat4 frame = glm::rotate(glm::translate(glm::mat4(1.0f), center),
                                        row % 2 ? glm::pi<float>() : 0.0f, glm::vec3(0, 1, 0));
    const int hue = static_cast<int>(rng.below(kPalette));
    const Material canvas = generated_surface(fmt::format("market_canvas_{}", hue),
                                              kCanvas[static_cast<std::size_t>(hue)], 0.9f);

    merged.add(wood, unit_box, box_at(frame, {0.0f, 0.5f, 0.6f}, {3.2f, 1.0f, 0.8f}));  // counter
    merged.add(canvas, unit_box,
               box_at(frame, {0.0f, 1.3f, -1.0f}, {3.4f, 2.6f, 0.1f}));  // back wall
    merged.add(canvas, unit_box, box_at(frame, {0.0f, 2.75f, 0.1f}, {3.6f, 0.08f, 2.6f}));  // roof
    for (float x : {-1.7f, 1.7f})
      merged.add(metal, unit_box, box_at(frame, {x, 1.35f, 1.2f}, {0.08f, 2.7f, 0.08f}));  // posts
    for (int g = 0; g < 3; ++g) {
      const glm::vec3 size(rng.uniform(0.2f, 0.6f), rng.uniform(0.1f, 0.4f),
                           rng.uniform(0.2f, 0.5f));
      merged.add(goods, unit_box,
                 box_at(frame, {rng.uniform(-1.2f, 1.2f), 1.0f + 0.5f * size.y, 0.6f}, size));
    }
    // A crate stack in the aisle in front of every other stall: occluders for shadow rays.
    if (rng.chance(0.5f)) {
      const float h = rng.uniform(0.5f, 1.4f);
      merged.add(crate, unit_box,
                 box_at(frame, {rng.uniform(-1.5f, 1.5f), 0.5f * h, 2.1f}, {0.7f, h, 0.7f}));
    }

    // Lantern string under the roof's front edge, sagging in the middle.
    for (std::uint32_t k = 0; k < p.lanterns_per_stall; ++k) {
      const float u = p.lanterns_per_stall > 1
                          ? static_cast<float>(k) / static_cast<float>(p.lanterns_per_stall - 1)
                          : 0.5f;
      const float x = -1.7f + 3.4f * u;
      const float y = 2.55f - 0.35f * (1.0f - (2.0f * u - 1.0f) * (2.0f * u - 1.0f));
      const int glow = static_cast<int>(rng.below(kPalette));
      const float radiance = log_uniform(rng, p.lantern_radiance);
      // Radiance bins (log-spaced) keep the material count small: bin centre stands for the bin.
      const float t = p.lantern_radiance.y > p.lantern_radiance.x && p.lantern_radiance.x > 0.0f
                          ? std::log(radiance / p.lantern_radiance.x) /
                                std::log(p.lantern_radiance.y / p.lantern_radiance.x)
                          : 0.0f;
      const int bin = std::min(static_cast<int>(t * kRadianceBins), kRadianceBins - 1);
      const float bin_radiance =
          p.lantern_radiance.x > 0.0f
              ? p.lantern_radiance.x * std::pow(p.lantern_radiance.y / p.lantern_radiance.x,
                                                (static_cast<float>(bin) + 0.5f) / kRadianceBins)
              : p.lantern_radiance.y;
      merged.add(generated_emitter(fmt::format("market_lantern_{}_{}", glow, bin),
                                   kGlow[static_cast<std::size_t>(glow)], bin_radiance),
                 lantern, glm::translate(frame, {x, y, 1.25f}));
    }
    // Sign: a strip of emissive quads on the back wall, facing the aisle (or one textured panel
    // over the same area).
    const std::uint32_t sign_cols = std::max<std::uint32_t>(1, (p.sign_quads + 1) / 2);
    if (sign_image >= 0 && p.sign_quads > 0) {
      const std::uint32_t sign_rows = (p.sign_quads + sign_cols - 1) / sign_cols;
      const glm::vec3 size(0.32f * static_cast<float>(sign_cols),
                           0.17f * static_cast<float>(sign_rows), 1.0f);
      const glm::mat4 m = glm::scale(
          glm::translate(frame, {0.0f, 2.05f + 0.085f * static_cast<float>(sign_rows - 1), -0.94f}),
          size);
      Material sign = generated_emitter(fmt::format("market_sign_texture_{}", hue),
                                        kGlow[static_cast<std::size_t>(hue)], 60.0f);
      sign.emissive_texture.image = sign_image;
      merged.add(sign, sign_panel, m);
    }
    for (std::uint32_t q = 0; sign_image < 0 && q < p.sign_quads; ++q) {
      const float x =
          (static_cast<float>(q % sign_cols) - 0.5f * static_cast<float>(sign_cols - 1)) * 0.32f;
      const float y = 2.05f + 0.17f * static_cast<float>(q / sign_cols);
      const glm::mat4 m = glm::scale(
          glm::rotate(glm::translate(frame, {x, y, -0.94f}), glm::half_pi<float>(), {1, 0, 0}),
          glm::vec3(0.28f, 1.0f, 0.14f));
      merged.add(generated_emitter(fmt::format("market_sign_{}", hue),
                                   kGlow[static_cast<std::size_t>(hue)], 60.0f),
                 sign_quad, m);
    }
    // Lights: a spot over the counter, then bulbs along the lantern string.
    for (std::uint32_t k = 0; k < p.lights_per_stall; ++k) {
      Light l;
      const glm::vec3 warm = kGlow[rng.below(kPalette)];
      l.color = warm;
      l.intensity = log_uniform(rng, p.light_intensity);
      if (k == 0) {
        l.type = LightType::Spot;
        l.name = fmt::format("stall{}_spot", s);
        l.position = glm::vec3(frame * glm::vec4(0.0f, 2.6f, 0.6f, 1.0f));
        l.rotation = look_at_orientation(glm::vec3(0.0f), glm::vec3(0, -1, 0));
        l.inner_cone = glm::radians(30.0f);
        l.outer_cone = glm::radians(50.0f);
        l.intensity *= 3.0f;
      } else {
        l.type = LightType::Point;
        l.name = fmt::format("stall{}_bulb{}", s, k);
        l.position = glm::vec3(
            frame * glm::vec4(rng.uniform(-1.6f, 1.6f), rng.uniform(2.0f, 2.4f), 1.1f, 1.0f));
      }
      if (rng.chance(p.flicker_fraction)) {
        l.behaviour = FlickerBehaviour{0.3f, 1.0f, rng.uniform(4.0f, 14.0f),
                                       static_cast<std::uint32_t>(rng.next())};
      } else if (k > 0 && rng.chance(p.moving_light_fraction)) {
        l.behaviour = OrbitBehaviour{l.position, 0.15f, rng.uniform(1.0f, 3.0f), glm::vec3(0, 1, 0),
                                     rng.uniform(0.0f, 6.2831853f)};
      }
      builder.add_light(std::move(l));
    }
  }

  // Ground under the whole market.
  {
    const glm::vec2 ground(2.0f * half_w + 24.0f, 2.0f * half_d + 24.0f);
    const std::uint32_t mat =
        builder.add_material(generated_surface("market_ground", {0.18f, 0.17f, 0.16f}, 0.9f));
    const std::uint32_t mesh = builder.add_mesh(make_plane(ground), where + ": ground");
    builder.add_instance("market_ground", mesh, mat, Transform{});
  }
  for (auto& [name, part] : merged.parts) {
    part.second.name = name;
    const std::uint32_t mat = builder.add_material(part.first);
    const std::uint32_t mesh =
        builder.add_mesh(std::move(part.second), fmt::format("{}: merged mesh '{}'", where, name));
    builder.add_instance(name, mesh, mat, Transform{});
  }

  // Movers: carts orbiting aisle points; every 4th is a spinning glowing sign.
  if (p.movers > 0) {
    const std::uint32_t cart_mesh =
        builder.add_mesh(make_box({1.2f, 1.0f, 0.8f}), where + ": cart");
    const std::uint32_t cart_mat =
        builder.add_material(generated_surface("market_cart", {0.5f, 0.1f, 0.08f}, 0.5f));
    const std::uint32_t spinner_mesh =
        builder.add_mesh(make_box({1.0f, 0.6f, 0.05f}), where + ": spinner");
    const std::uint32_t spinner_mat =
        builder.add_material(generated_emitter("market_spinner", {0.4f, 0.9f, 1.0f}, 150.0f));
    const std::uint32_t aisles = std::max<std::uint32_t>(1, rows / 2);
    for (std::uint32_t i = 0; i < p.movers; ++i) {
      const std::uint32_t aisle = rng.below(aisles);
      const float z = (static_cast<float>(2 * aisle) + 0.5f) * kPitchZ - half_d;
      const glm::vec3 c(rng.uniform(-half_w, half_w), 0.0f, z);
      Transform t;
      if (i % 4 == 3) {
        t.translation = c + glm::vec3(0.0f, 3.4f, 0.0f);
        builder.add_instance(fmt::format("spinner{}", i), spinner_mesh, spinner_mat, t,
                             RotateBehaviour{glm::vec3(0, 1, 0), rng.uniform(0.5f, 2.0f)});
      } else {
        t.translation = c + glm::vec3(0.0f, 0.5f, 0.0f);
        OrbitBehaviour orbit{t.translation, rng.uniform(1.0f, 1.5f), rng.uniform(0.2f, 0.6f),
                             glm::vec3(0, 1, 0), rng.uniform(0.0f, 6.2831853f)};
        builder.add_instance(fmt::format("cart{}", i), cart_mesh, cart_mat, t, orbit);
      }
    }
  }

  // A loop along the first aisle, across, back along the last aisle and across again.
  const float z0 = 0.5f * kPitchZ - half_d;
  const float z1 = std::max(
      z0,
      (static_cast<float>(2 * std::max<std::uint32_t>(1, rows / 2) - 2) + 0.5f) * kPitchZ - half_d);
  const float x0 = -half_w - 2.0f, x1 = half_w + 2.0f;
  const std::array<glm::vec3, 5> corners = {
      {{x0, 1.7f, z0}, {x1, 1.7f, z0}, {x1, 2.5f, z1}, {x0, 1.7f, z1}, {x0, 1.7f, z0}}};
  constexpr int kPerSide = 3;
  add_generated_camera_loop(
      builder.level(), p.path_name, p.path_duration, 4 * kPerSide, [&](int i) {
        const int side = std::min(i / kPerSide, 3);
        const float u = static_cast<float>(i - side * kPerSide) / kPerSide;
        const glm::vec3& from = corners[static_cast<std::size_t>(side)];
        const glm::vec3& to = corners[static_cast<std::size_t>(side + 1)];
        const glm::vec3 eye = glm::mix(from, to, u);
        const glm::vec3 ahead =
            glm::mix(from, to, std::min(u + 0.5f, 1.0f)) + glm::vec3(0.0f, -0.3f, 0.0f);
        return LoopPose{
            eye, glm::length(ahead - eye) > 0.5f ? ahead : eye + glm::vec3(1.0f, -0.2f, 0.0f)};
      });
}

}  // namespace lantern
