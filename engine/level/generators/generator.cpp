// Generator dispatch: "type" -> the generator's parameter reader and builder.
#include "engine/level/generators/generator.h"

#include <fmt/format.h>

#include "engine/level/generators/light_field.h"
#include "engine/level/generators/light_panels.h"
#include "engine/level/generators/night_market.h"
#include "engine/level/json_level_reader.h"
#include "engine/scene/camera.h"
#include "engine/scene/level.h"

namespace lantern {

void run_generator(JsonObject& params, JsonLevelReader& reader) {
  const std::string type = params.string("type");
  if (type == "night_market") {
    NightMarketParams p;
    p.seed = static_cast<std::uint64_t>(params.integer("seed", 1, 0, 0x7FFFFFFFFFFFFFFFll));
    p.stalls = static_cast<std::uint32_t>(params.integer("stalls", p.stalls, 1, 20000));
    p.lanterns_per_stall = static_cast<std::uint32_t>(
        params.integer("lanterns_per_stall", p.lanterns_per_stall, 0, 512));
    p.lantern_subdivisions = static_cast<std::uint32_t>(
        params.integer("lantern_subdivisions", p.lantern_subdivisions, 0, 3));
    p.lights_per_stall =
        static_cast<std::uint32_t>(params.integer("lights_per_stall", p.lights_per_stall, 0, 64));
    p.sign_quads = static_cast<std::uint32_t>(params.integer("sign_quads", p.sign_quads, 0, 256));
    if (params.has("sign_texture")) p.sign_texture = reader.existing_file(params, "sign_texture");
    p.movers = static_cast<std::uint32_t>(params.integer("movers", p.movers, 0, 10000));
    p.flicker_fraction = params.number("flicker_fraction", p.flicker_fraction);
    p.moving_light_fraction = params.number("moving_light_fraction", p.moving_light_fraction);
    p.lantern_radiance = params.vec2("lantern_radiance", p.lantern_radiance);
    p.light_intensity = params.vec2("light_intensity", p.light_intensity);
    p.path_name = params.string("path", p.path_name);
    p.path_duration = params.number("path_duration", p.path_duration);
    if (p.flicker_fraction < 0.0f || p.flicker_fraction > 1.0f)
      params.fail("flicker_fraction", "must be in [0, 1]");
    if (p.moving_light_fraction < 0.0f || p.moving_light_fraction > 1.0f)
      params.fail("moving_light_fraction", "must be in [0, 1]");
    if (p.lantern_radiance.x < 0.0f || p.lantern_radiance.y < p.lantern_radiance.x)
      params.fail("lantern_radiance", "need 0 <= min <= max (negative radiance is not allowed)");
    if (p.light_intensity.x < 0.0f || p.light_intensity.y < p.light_intensity.x)
      params.fail("light_intensity", "need 0 <= min <= max");
    if (p.path_duration <= 0.0f) params.fail("path_duration", "must be > 0");
    generate_night_market(p, reader.builder(),
                          fmt::format("{}: {}", reader.file().string(), params.pointer()));
    return;
  }
  if (type == "light_field") {
    LightFieldParams p;
    p.seed = static_cast<std::uint64_t>(params.integer("seed", 1, 0, 0x7FFFFFFFFFFFFFFFll));
    p.emitter_triangles = static_cast<std::uint32_t>(
        params.integer("emitter_triangles", p.emitter_triangles, 2, 2000000));
    p.extent = params.number("extent", p.extent);
    p.pillars = static_cast<std::uint32_t>(params.integer("pillars", p.pillars, 0, 10000));
    p.radiance = params.vec2("radiance", p.radiance);
    p.quad_size = params.number("quad_size", p.quad_size);
    p.path_name = params.string("path", p.path_name);
    p.path_duration = params.number("path_duration", p.path_duration);
    if (!(p.extent >= 1.0f && p.extent <= 10000.0f)) params.fail("extent", "must be in [1, 10000]");
    if (!(p.quad_size > 0.0f && p.quad_size <= 10.0f)) params.fail("quad_size", "must be in (0, 10]");
    if (!(p.radiance.x > 0.0f && p.radiance.y >= p.radiance.x && p.radiance.y < 1e9f))
      params.fail("radiance", "need 0 < min <= max < 1e9");
    if (p.path_duration <= 0.0f) params.fail("path_duration", "must be > 0");
    generate_light_field(p, reader.builder(),
                         fmt::format("{}: {}", reader.file().string(), params.pointer()));
    return;
  }
  if (type == "light_panels") {
    LightPanelsParams p;
    p.seed = static_cast<std::uint64_t>(params.integer("seed", 1, 0, 0x7FFFFFFFFFFFFFFFll));
    p.panels = static_cast<std::uint32_t>(params.integer("panels", p.panels, 1, 1000));
    p.emitter_triangles = static_cast<std::uint32_t>(
        params.integer("emitter_triangles", p.emitter_triangles, 2, 4000000));
    p.panel_size = params.vec2("panel_size", p.panel_size);
    p.extent = params.number("extent", p.extent);
    p.pillars = static_cast<std::uint32_t>(params.integer("pillars", p.pillars, 0, 10000));
    p.awnings = static_cast<std::uint32_t>(params.integer("awnings", p.awnings, 0, 10000));
    p.radiance = params.vec2("radiance", p.radiance);
    p.height = params.number("height", p.height);
    p.path_name = params.string("path", p.path_name);
    p.path_duration = params.number("path_duration", p.path_duration);
    if (p.emitter_triangles % (2 * p.panels) != 0)
      params.fail("emitter_triangles",
                  fmt::format("must be a multiple of 2 x panels = {}", 2 * p.panels));
    if (!(p.extent >= 4.0f && p.extent <= 10000.0f)) params.fail("extent", "must be in [4, 10000]");
    if (!(p.panel_size.x > 0.0f && p.panel_size.y > 0.0f && p.panel_size.x <= p.extent &&
          p.panel_size.y <= p.extent))
      params.fail("panel_size", "need 0 < size <= extent");
    if (!(p.height > 0.5f && p.height < 1000.0f)) params.fail("height", "must be in (0.5, 1000)");
    if (!(p.radiance.x > 0.0f && p.radiance.y >= p.radiance.x && p.radiance.y < 1e9f))
      params.fail("radiance", "need 0 < min <= max < 1e9");
    if (p.path_duration <= 0.0f) params.fail("path_duration", "must be > 0");
    generate_light_panels(p, reader.builder(),
                          fmt::format("{}: {}", reader.file().string(), params.pointer()));
    return;
  }
  params.fail(
      "type",
      fmt::format("unknown generator type '{}' (night_market, light_field, light_panels)", type));
}

Material generated_surface(const std::string& name, glm::vec3 color, float roughness) {
  Material m;
  m.name = name;
  m.base_color = glm::vec4(color, 1.0f);
  m.metallic = 0.0f;
  m.roughness = roughness;
  return m;
}

Material generated_emitter(const std::string& name, glm::vec3 color, float radiance) {
  Material m = generated_surface(name, glm::vec3(0.05f), 0.6f);
  m.emissive_factor = color;
  m.emissive_strength = radiance;
  return m;
}

void use_generated_camera_path(Level& level, const std::string& path_name) {
  if (level.camera_path.empty()) level.camera_path = path_name;
  if (!level.has_camera) {
    const PathPose pose = level.find_path(path_name)->evaluate(0.0f);
    level.camera.position = pose.position;
    level.camera.orientation = pose.orientation;
    level.camera.yfov = glm::radians(60.0f);
    level.has_camera = true;
  }
}

void add_generated_camera_loop(Level& level, const std::string& path_name, float duration,
                               int steps, const std::function<LoopPose(int)>& pose) {
  if (!level.find_path(path_name)) {
    CameraPath path;
    path.name = path_name;
    path.loop = true;
    for (int i = 0; i <= steps; ++i) {
      const LoopPose at = pose(i);
      path.keys.push_back({duration * static_cast<float>(i) / static_cast<float>(steps), at.eye,
                           look_at_orientation(at.eye, at.target), std::nullopt});
    }
    path.keys.back().orientation = path.keys.front().orientation;
    level.paths.push_back(std::move(path));
  }
  use_generated_camera_path(level, path_name);
}

}  // namespace lantern
