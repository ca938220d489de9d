// The baseline integrator end to end on the GPU (render_offline, as `lantern render` runs it):
// cornell_lights renders finite and lit, pixels that see an emitter's front face show exactly its
// radiance, and a Lambertian plane under a point light matches the closed form rho/pi * I/h^2.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/level/level_loader.h"
#include "engine/level/primitives.h"
#include "lighting/integrators/offline_render.h"
#include "lighting/scene/frame_constants.h"
#include "lighting/scene/scene_data.h"
#include "runtime/gpu/shader_library.h"
#include "shared/color.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {

using lighting::OfflineRenderRequest;
using lighting::render_offline;

class BaselineRenderTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;
};

// Camera ray through image position (x, y) in pixels (same construction as baseline.comp).
gpu::BvhRay camera_ray(const Camera& camera, std::uint32_t w, std::uint32_t h, float x, float y) {
  const glm::mat4 inv = glm::inverse(lighting::camera_view_proj(camera, w, h));
  const glm::vec2 ndc =
      glm::vec2(x / static_cast<float>(w), y / static_cast<float>(h)) * 2.0f - 1.0f;
  const glm::vec4 a = inv * glm::vec4(ndc, 0.0f, 1.0f);
  const glm::vec4 b = inv * glm::vec4(ndc, 0.5f, 1.0f);
  const glm::vec3 dir = glm::normalize(glm::vec3(b) / b.w - glm::vec3(a) / a.w);
  return gpu::bvh_make_ray(camera.position, dir, 0.0f, gpu::kBvhMiss);
}

// World-space front normal of triangle `t` of instance `i` (winding, mirrored by det < 0).
glm::vec3 front_normal(const Level& level, std::uint32_t i, std::uint32_t t) {
  const Instance& inst = level.instances[i];
  const Mesh& mesh = level.meshes[inst.mesh];
  glm::vec3 p[3];
  for (int k = 0; k < 3; ++k) {
    p[k] = glm::vec3(inst.world * glm::vec4(mesh.positions[mesh.indices[3 * t + k]], 1.0f));
  }
  glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
  return glm::determinant(glm::mat3(inst.world)) < 0.0f ? -n : n;
}

TEST_F(BaselineRenderTest, CornellLightsIsFiniteLitAndShowsEmittersExactly) {
  Level level = load_level_argument("cornell_lights");
  // Emitters reflect nothing here, so a pixel that sees one shows exactly its emitted radiance.
  for (Material& m : level.materials) {
    if (!m.emissive()) continue;
    m.base_color = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    m.metallic = 0.0f;
    m.specular_factor = 0.0f;
  }
  OfflineRenderRequest request;
  request.width = 160;
  request.height = 90;
  request.frames = 3;
  request.average = true;
  const auto result = render_offline(device, shaders, level, request);
  ASSERT_EQ(result.images.size(), 1u);
  ASSERT_EQ(result.frame_ms.size(), 3u);
  const runtime::ImageRGBA32F& image = result.images[0];
  EXPECT_EQ(image.count_non_finite(), 0u);

  double sum = 0.0;
  for (std::uint32_t y = 0; y < image.height; ++y) {
    for (std::uint32_t x = 0; x < image.width; ++x) {
      const float* p = image.at(x, y);
      sum += gpu::luminance(glm::vec3(p[0], p[1], p[2]));
    }
  }
  EXPECT_GT(sum / (image.width * image.height), 0.0);

  // Pixels whose centre and four corner rays all hit the front of one emissive instance.
  const lighting::SceneData scene = lighting::build_scene_data(level);
  int checked = 0;
  for (std::uint32_t y = 0; y < image.height; ++y) {
    for (std::uint32_t x = 0; x < image.width; ++x) {
      gpu::BvhHit hit{};
      const float cx = static_cast<float>(x) + 0.5f;
      const float cy = static_cast<float>(y) + 0.5f;
      const gpu::BvhRay ray = camera_ray(level.camera, image.width, image.height, cx, cy);
      if (!scene.bvh.trace_closest(ray, hit)) continue;
      const Material& material = level.materials[level.instances[hit.instance].material];
      if (!material.emissive()) continue;
      if (glm::dot(front_normal(level, hit.instance, hit.primitive), glm::vec3(ray.direction)) >=
          0.0f) {
        continue;
      }
      bool interior = true;
      for (const glm::vec2 d : {glm::vec2(-0.5f, -0.5f), glm::vec2(0.5f, -0.5f),
                                glm::vec2(-0.5f, 0.5f), glm::vec2(0.5f, 0.5f)}) {
        gpu::BvhHit corner{};
        interior =
            interior &&
            scene.bvh.trace_closest(
                camera_ray(level.camera, image.width, image.height, cx + d.x, cy + d.y), corner) &&
            corner.instance == hit.instance;
      }
      if (!interior) continue;
      const glm::vec3 expected = material.emitted_radiance();
      const float* p = image.at(x, y);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(p[c], expected[c], 1e-5f * expected[c] + 1e-6f)
            << "pixel (" << x << ", " << y << ") channel " << c;
      }
      ++checked;
    }
  }
  EXPECT_GE(checked, 10) << "too few pixels see an emitter: the test proves nothing";
}

// One Lambertian plane (y = 0, facing +Y) lit from above, seen by a camera straight above the
// origin: the centre pixel sees the origin, where the radiance is rho/pi times the irradiance
// (one light: sampling it is exact, one frame suffices).
Level lit_plane_level(float rho, const Light& light) {
  Level level;
  level.name = "lit_plane";
  level.meshes.push_back(make_plane(glm::vec2(20.0f, 20.0f)));
  Material m;
  m.base_color = glm::vec4(rho, rho, rho, 1.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.specular_factor = 0.0f;
  level.materials.push_back(m);
  Instance inst;
  inst.name = "plane";
  level.instances.push_back(inst);
  level.lights.push_back(light);
  level.camera.position = glm::vec3(0.0f, 4.0f, 0.0f);
  level.camera.orientation = look_at_orientation(level.camera.position, glm::vec3(0.0f));
  level.camera.yfov = 0.6f;
  level.has_camera = true;
  return level;
}

runtime::ImageRGBA32F render_single(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                    const Level& level) {
  OfflineRenderRequest request;
  request.width = 41;  // odd: the centre pixel's centre is the image centre
  request.height = 31;
  auto result = render_offline(device, shaders, level, request);
  EXPECT_EQ(result.images.size(), 1u);
  EXPECT_EQ(result.images.at(0).count_non_finite(), 0u);
  return result.images.at(0);
}

void expect_centre(const runtime::ImageRGBA32F& image, glm::vec3 expected) {
  const float* centre = image.at(image.width / 2, image.height / 2);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(centre[c], expected[c], 0.01f * expected[c]) << "channel " << c;
  }
}

constexpr float kRho = 0.5f;
constexpr float kHeight = 1.5f;
const glm::vec3 kColor(3.0f, 2.0f, 1.0f);

TEST_F(BaselineRenderTest, LambertPlaneUnderPointLightMatchesClosedForm) {
  Light light;
  light.type = LightType::Point;
  light.color = kColor;
  light.position = glm::vec3(0.0f, kHeight, 0.0f);
  const runtime::ImageRGBA32F image = render_single(device, shaders, lit_plane_level(kRho, light));
  expect_centre(image, kRho / 3.14159265f * kColor / (kHeight * kHeight));
  // Farther from the light the image gets darker (the falloff is there at all).
  EXPECT_LT(image.at(0, image.height / 2)[0], image.at(image.width / 2, image.height / 2)[0]);
}

// A spot pointing straight down: on its axis it is a point light; outside its cone, black.
TEST_F(BaselineRenderTest, LambertPlaneUnderSpotLightMatchesClosedFormAndCone) {
  Light light;
  light.type = LightType::Spot;
  light.color = kColor;
  light.position = glm::vec3(0.0f, kHeight, 0.0f);
  light.rotation = glm::angleAxis(-glm::half_pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f));
  light.inner_cone = 0.05f;
  light.outer_cone = 0.1f;
  ASSERT_NEAR(light.direction().y, -1.0f, 1e-5f);
  const runtime::ImageRGBA32F image = render_single(device, shaders, lit_plane_level(kRho, light));
  expect_centre(image, kRho / 3.14159265f * kColor / (kHeight * kHeight));
  EXPECT_EQ(image.at(0, 0)[0], 0.0f) << "a corner lies outside the 0.1 rad cone";
}

// A directional light shining straight down with irradiance E: radiance rho/pi * E everywhere.
TEST_F(BaselineRenderTest, LambertPlaneUnderDirectionalLightMatchesClosedForm) {
  Light light;
  light.type = LightType::Directional;
  light.color = kColor;
  light.rotation = glm::angleAxis(-glm::half_pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f));
  const runtime::ImageRGBA32F image = render_single(device, shaders, lit_plane_level(kRho, light));
  expect_centre(image, kRho / 3.14159265f * kColor);
  const float* corner = image.at(0, 0);
  EXPECT_NEAR(corner[0], kRho / 3.14159265f * kColor[0], 0.01f * kColor[0]);
}

}  // namespace
}  // namespace lantern
