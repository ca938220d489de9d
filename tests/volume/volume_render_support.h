// Shared by the media GPU tests: one averaged offline render of a level, and the camera ray of a
// pixel as the renderer builds it (direction from inv_view_proj, no jitter; origin the camera
// position), in double precision.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <string>

#include "lighting/integrators/offline_render.h"
#include "lighting/scene/frame_constants.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::test {

struct VolumeRender {
  std::uint32_t width = 64;
  std::uint32_t height = 36;
  std::uint32_t frames = 1;
  std::uint32_t spp = 4;  // the reference's samples per pixel per frame
  std::uint32_t seed = 3;
  bool animate = false;  // step the level (its camera path) every frame; else one still frame
};

// The mean of `r.frames` frames of `integrator` (static unless r.animate); no non-finite pixel.
inline runtime::ImageRGBA32F render_volume_level(runtime::Device& device,
                                                 runtime::ShaderLibrary& shaders,
                                                 const Level& level, const std::string& integrator,
                                                 const VolumeRender& r) {
  lighting::OfflineRenderRequest request;
  request.integrator.name = integrator;
  if (integrator == "reference") request.integrator.spp = r.spp;
  request.width = r.width;
  request.height = r.height;
  request.frames = r.frames;
  request.average = true;
  request.animate = r.animate;
  request.seed = r.seed;
  auto result = lighting::render_offline(device, shaders, level, request);
  EXPECT_EQ(result.images.size(), 1u);
  EXPECT_EQ(result.images[0].count_non_finite(), 0u);
  return result.images[0];
}

// A level's JSON object text with a "volumes" array of `volume` (one entry's JSON) added, or
// unchanged when `volume` is empty: the same level with and without its media.
inline std::string with_volume(std::string level, const std::string& volume) {
  if (volume.empty()) return level;
  level.insert(level.rfind('}'), R"(, "volumes": [ )" + volume + " ]");
  return level;
}

// A 6 m floor under a point light (intensity 20 at kFloorLight), seen from 4 m straight above.
inline const glm::dvec3 kFloorCamera(0.0, 4.0, 0.0);
inline const glm::dvec3 kFloorLight(0.8, 3.0, -0.6);
inline constexpr const char* kFloorUnderPointLight = R"({
  "materials": { "floor": { "base_color": [0.6, 0.6, 0.6], "roughness": 1.0 } },
  "primitives": [ { "type": "plane", "size": [6, 6], "material": "floor" } ],
  "lights": [ { "type": "point", "position": [0.8, 3.0, -0.6], "color": [1, 1, 1], "intensity": 20 } ],
  "camera": { "position": [0.0, 4.0, 0.0], "target": [0.0, 0.0, -0.001], "yfov_deg": 40 } })";

struct PixelRay {
  glm::dvec3 origin;
  glm::dvec3 dir;  // unit
};

inline PixelRay pixel_ray(const Level& level, std::uint32_t width, std::uint32_t height,
                          std::uint32_t x, std::uint32_t y) {
  const gpu::FrameConstants fc = lighting::make_frame_constants(level.camera, width, height, 0, 1, {});
  const glm::dmat4 inv(fc.inv_view_proj);
  const glm::dvec2 ndc((x + 0.5) / width * 2.0 - 1.0, (y + 0.5) / height * 2.0 - 1.0);
  const glm::dvec4 a = inv * glm::dvec4(ndc, 0.0, 1.0);
  const glm::dvec4 b = inv * glm::dvec4(ndc, 0.5, 1.0);
  const glm::dvec3 o = glm::dvec3(a) / a.w;
  // From the camera itself (the media passes start there), through the pixel's near-plane point.
  return {glm::dvec3(fc.camera_position), glm::normalize(glm::dvec3(b) / b.w - o)};
}

// Where pixel (x, y)'s camera ray meets the plane y = 0.
inline glm::dvec3 floor_point(const Level& level, std::uint32_t width, std::uint32_t height,
                              std::uint32_t x, std::uint32_t y) {
  const PixelRay r = pixel_ray(level, width, height, x, y);
  return r.origin + r.dir * (-r.origin.y / r.dir.y);
}

}  // namespace lantern::test
