// Levels built in code for the numerical-extremes tests, and the renders they compare.
//
// The test room: a 6 x 6 m Lambertian floor (rho 0.5), a back wall, a Lambertian occluder box and
// a glossy box, lit only by downward-facing emissive quads (area lights; no analytic lights, so
// direct lighting is invariant under a uniform scale of the scene and the camera). The camera
// looks down at the floor from (0, 2.5, 4.5). Everything is plain Level data, so a test can push
// values through that no loader would produce (slivers, huge albedo, 1e-8..1e8 radiance).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/level/level_builder.h"
#include "engine/level/primitives.h"
#include "engine/scene/level.h"
#include "engine/world/world.h"
#include "lighting/frame/headless_session.h"
#include "lighting/integrators/offline_render.h"
#include "runtime/image/image.h"
#include "runtime/image/image_metrics.h"

namespace lantern::extremes {

using lighting::IntegratorConfig;
using Settings = std::vector<std::pair<std::string, std::string>>;

struct Emitter {
  glm::vec3 position{0.0f, 2.0f, 0.0f};  // centre of the quad, which faces -Y
  float radiance = 10.0f;                // W/(sr m^2), white
  float size = 0.5f;                     // edge length, metres
};

inline Material emissive(float radiance) {
  Material m = make_lambert(0.0f);
  m.emissive_factor = glm::vec3(1.0f);
  m.emissive_strength = radiance;
  return m;
}

inline Instance place(std::string name, std::uint32_t mesh, std::uint32_t material,
                      const glm::mat4& world) {
  Instance inst;
  inst.name = std::move(name);
  inst.mesh = mesh;
  inst.material = material;
  inst.world = world;
  inst.transform = Transform::from_matrix(world);
  return inst;
}

inline std::uint32_t add_mesh(Level& level, Mesh mesh) {
  level.meshes.push_back(std::move(mesh));
  return static_cast<std::uint32_t>(level.meshes.size() - 1);
}
inline std::uint32_t add_material(Level& level, Material m) {
  level.materials.push_back(std::move(m));
  return static_cast<std::uint32_t>(level.materials.size() - 1);
}

// The room without emitters (materials 0 floor, 1 occluder, 2 glossy).
inline Level room(const std::string& name = "extremes_room") {
  Level level;
  level.name = name;
  const std::uint32_t floor_mat = add_material(level, make_lambert(0.5f));
  const std::uint32_t box_mat = add_material(level, make_lambert(0.6f));
  Material glossy = make_lambert(0.7f);
  glossy.roughness = 0.35f;
  glossy.specular_factor = 1.0f;
  const std::uint32_t glossy_mat = add_material(level, glossy);
  const std::uint32_t plane = add_mesh(level, make_plane(glm::vec2(6.0f, 6.0f)));
  const std::uint32_t box = add_mesh(level, make_box(glm::vec3(0.8f, 0.8f, 0.8f)));
  level.instances.push_back(place("floor", plane, floor_mat, glm::mat4(1.0f)));
  level.instances.push_back(place(
      "back", plane, floor_mat,
      glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 3.0f, -3.0f)) *
          glm::mat4_cast(glm::angleAxis(glm::half_pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f)))));
  level.instances.push_back(
      place("occluder", box, box_mat,
            glm::translate(glm::mat4(1.0f), glm::vec3(-0.9f, 0.4f, 0.0f)) *
                glm::mat4_cast(glm::angleAxis(0.4f, glm::vec3(0.0f, 1.0f, 0.0f)))));
  level.instances.push_back(place(
      "glossy", box, glossy_mat,
      glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.3f, 0.6f)) *
          glm::scale(glm::mat4(1.0f), glm::vec3(0.75f))));
  level.camera.position = glm::vec3(0.0f, 2.5f, 4.5f);
  level.camera.orientation = look_at_orientation(level.camera.position, glm::vec3(0.0f, 0.4f, 0.0f));
  level.camera.yfov = 0.9f;
  level.has_camera = true;
  return level;
}

// Adds downward-facing emissive quads, one material each.
inline void add_emitters(Level& level, const std::vector<Emitter>& emitters) {
  const glm::mat4 face_down =
      glm::mat4_cast(glm::angleAxis(glm::pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f)));
  for (std::size_t i = 0; i < emitters.size(); ++i) {
    const Emitter& e = emitters[i];
    const std::uint32_t mesh = add_mesh(level, make_plane(glm::vec2(e.size, e.size)));
    const std::uint32_t mat = add_material(level, emissive(e.radiance));
    level.instances.push_back(place("emitter" + std::to_string(i), mesh, mat,
                                    glm::translate(glm::mat4(1.0f), e.position) * face_down));
  }
}

inline Level lit_room(const std::vector<Emitter>& emitters, const std::string& name = "lit_room") {
  Level level = room(name);
  add_emitters(level, emitters);
  return level;
}

// The two-light room most tests use: a bright quad over the middle, a dim one to the side.
inline std::vector<Emitter> two_lights(float scale = 1.0f) {
  return {{glm::vec3(0.3f, 2.0f, 0.5f), 20.0f * scale, 0.6f},
          {glm::vec3(-1.8f, 1.5f, -1.0f), 4.0f * scale, 0.4f}};
}

// Multiplies every emitter's radiance by k.
inline void scale_radiance(Level& level, float k) {
  for (Material& m : level.materials)
    if (m.emissive()) m.emissive_strength *= k;
}

// Applies `m` (uniform scale s and a translation) to every instance and the camera; the near
// plane scales with s so the camera sees the same picture.
inline void transform_level(Level& level, float s, const glm::vec3& t) {
  const glm::mat4 m = glm::translate(glm::mat4(1.0f), t) * glm::scale(glm::mat4(1.0f), glm::vec3(s));
  for (Instance& inst : level.instances) {
    inst.world = m * inst.world;
    inst.transform = Transform::from_matrix(inst.world);
  }
  level.camera.position = glm::vec3(m * glm::vec4(level.camera.position, 1.0f));
  level.camera.znear *= s;
  if (level.camera.zfar > 0.0f) level.camera.zfar *= s;
}

inline IntegratorConfig baseline() { return {.name = "baseline"}; }
inline IntegratorConfig restir(Settings settings = {}) {
  return {.name = "restir", .settings = std::move(settings)};
}
inline IntegratorConfig reference(std::uint32_t spp = 16) {
  return {.name = "reference", .spp = spp};
}

inline const char* name_of(const IntegratorConfig& c) { return c.name.c_str(); }

// The mean of `frames` frames of a static level (the first snapshot held still: temporal reuse
// accumulates history), or each frame when `average` is false.
inline std::vector<runtime::ImageRGBA32F> render_static(runtime::Device& device,
                                                        runtime::ShaderLibrary& shaders,
                                                        const Level& level,
                                                        const IntegratorConfig& config,
                                                        std::uint32_t frames, bool average = true,
                                                        std::uint32_t width = 64,
                                                        std::uint32_t height = 36,
                                                        std::uint32_t seed = 1) {
  lighting::OfflineRenderRequest request;
  request.integrator = config;
  request.width = width;
  request.height = height;
  request.frames = frames;
  request.average = average;
  request.animate = false;
  request.seed = seed;
  return lighting::render_offline(device, shaders, level, request).images;
}

inline runtime::ImageRGBA32F render_mean(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                         const Level& level, const IntegratorConfig& config,
                                         std::uint32_t frames, std::uint32_t width = 64,
                                         std::uint32_t height = 36, std::uint32_t seed = 1) {
  return render_static(device, shaders, level, config, frames, true, width, height, seed).at(0);
}

inline double max_channel(const runtime::ImageRGBA32F& image) {
  double m = 0.0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    if (i % 4 != 3) m = std::max(m, static_cast<double>(image.pixels[i]));
  return m;
}

inline double min_channel(const runtime::ImageRGBA32F& image) {
  double m = 0.0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    if (i % 4 != 3) m = std::min(m, static_cast<double>(image.pixels[i]));
  return m;
}

// |a - b| / b, or |a| when b is 0.
inline double rel_diff(double a, double b) { return b != 0.0 ? std::abs(a - b) / std::abs(b) : std::abs(a); }

}  // namespace lantern::extremes
