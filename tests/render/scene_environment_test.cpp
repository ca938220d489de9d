// The scene's environment map (GpuScene owns it; every integrator binds it through SceneHandles,
// lighting/scene/scene_buffers.h) on the GPU, through render_offline as `lantern render` runs it:
//   - sky pixels (G-buffer sky) of baseline and reference show the map's radiance along the
//     pixel's camera ray, exactly (a pixel whose ray lies within 1e-4 rad of a texel border may
//     show the neighbour texel);
//   - GpuScene's selection probability is env_power / (env_power + emitters' power);
//   - baseline (1 light sample per pixel per frame: environment or alias table) converges to the
//     reference on a box on a plane under an environment map and a sun: mean of 512 frames within
//     1% of the reference's image mean, and every 16x12-pixel block within 4%; ReSTIR (balance,
//     pairwise, with BSDF candidates) does too: mean of 64 frames within 3%, blocks within 8%;
//   - a few frames of baseline, reference and restir under synchronisation validation (the BVH
//     read as texel views and storage buffers, the env header rewritten by scene.upload) report
//     no hazard.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <memory>
#include <string>
#include <vector>

#include "engine/level/primitives.h"
#include "lighting/integrators/offline_render.h"
#include "lighting/lights/environment_map.h"
#include "lighting/scene/frame_constants.h"
#include "lighting/scene/gpu_scene.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/image/image_io.h"
#include "shared/environment.h"
#include "tests/runtime/gpu_test_support.h"
#include "tests/runtime/scratch_dir.h"

namespace lantern {
namespace {

using lighting::OfflineRenderRequest;

constexpr std::uint32_t kWidth = 64;
constexpr std::uint32_t kHeight = 36;

class SceneEnvironmentTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;
};

// A 20 x 20 grey plane at y = 0 (and optionally a unit box standing on it at the origin) under a
// 32 x 16 colour environment map (rotated), camera at `eye` looking at `target`.
Level env_level(const std::string& file, glm::vec3 eye, glm::vec3 target, bool box) {
  Level level;
  level.name = "scene_env_" + file;
  level.meshes.push_back(make_plane(glm::vec2(20.0f, 20.0f)));
  level.materials.push_back(make_lambert(0.6f));
  Instance plane;
  plane.name = "plane";
  level.instances.push_back(plane);
  if (box) {
    level.meshes.push_back(make_box(glm::vec3(1.0f)));
    Material m = make_lambert(0.8f);
    m.roughness = 0.4f;
    m.specular_factor = 0.5f;
    level.materials.push_back(m);
    Instance b;
    b.name = "box";
    b.mesh = 1;
    b.material = 1;
    b.transform.translation = glm::vec3(0.0f, 0.5f, 0.0f);
    b.world = b.transform.matrix();
    level.instances.push_back(b);
  }
  level.camera.position = eye;
  level.camera.orientation = look_at_orientation(eye, target);
  level.camera.yfov = 0.9f;
  level.has_camera = true;

  // A sky brighter towards the top, with a warm band and a bright spot: every texel distinct.
  const std::uint32_t w = 32;
  const std::uint32_t h = 16;
  runtime::ImageRGBA32F image(w, h);
  for (std::uint32_t y = 0; y < h; ++y) {
    for (std::uint32_t x = 0; x < w; ++x) {
      float* p = image.at(x, y);
      p[0] = 0.2f + 0.05f * static_cast<float>(x) + (y == 6 ? 1.0f : 0.0f);
      p[1] = 0.3f + 0.1f * static_cast<float>(h - y) + 0.003f * static_cast<float>(x);
      p[2] = 0.5f + 0.15f * static_cast<float>(h - y) + (x == 20 && y == 3 ? 30.0f : 0.0f);
      p[3] = 1.0f;
    }
  }
  const std::filesystem::path path = test::process_scratch_dir() / file;
  runtime::write_image(path, image);
  level.environment =
      EnvironmentMap{path, 1.0f, glm::quat(glm::radians(glm::vec3(0.0f, 35.0f, 0.0f)))};
  return level;
}

void add_sun(Level& level, float irradiance) {
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Directional;
  sun.color = glm::vec3(1.0f, 0.9f, 0.8f);
  sun.intensity = irradiance;
  sun.rotation =
      glm::quat(glm::vec3(0.0f, 0.0f, -1.0f), glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f)));
  level.lights.push_back(sun);
}

OfflineRenderRequest request_for(const std::string& integrator, std::uint32_t frames) {
  OfflineRenderRequest request;
  request.integrator.name = integrator;
  request.width = kWidth;
  request.height = kHeight;
  request.frames = frames;
  request.animate = false;
  return request;
}

// World direction of the camera ray through the centre of pixel (x, y).
glm::vec3 camera_dir(const Camera& camera, std::uint32_t x, std::uint32_t y) {
  const glm::mat4 inv = glm::inverse(lighting::camera_view_proj(camera, kWidth, kHeight));
  const glm::vec2 ndc = (glm::vec2(static_cast<float>(x), static_cast<float>(y)) + 0.5f) /
                            glm::vec2(static_cast<float>(kWidth), static_cast<float>(kHeight)) *
                            2.0f -
                        1.0f;
  const glm::vec4 a = inv * glm::vec4(ndc, 0.0f, 1.0f);
  const glm::vec4 b = inv * glm::vec4(ndc, 0.5f, 1.0f);
  return glm::normalize(glm::vec3(b) / b.w - glm::vec3(a) / a.w);
}

// Every pixel whose ray points upwards (nothing above the plane: sky) equals the map's
// radiance along it (or a neighbouring texel's when the ray is within 1e-4 rad of a border).
void expect_sky_is_environment(const runtime::ImageRGBA32F& image, const Level& level,
                               const lighting::EnvironmentDistribution& env, const char* what) {
  int sky = 0;
  int mismatches = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y) {
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const glm::vec3 dir = camera_dir(level.camera, x, y);
      if (dir.y < 0.02f) continue;
      ++sky;
      const glm::vec3 got(image.at(x, y)[0], image.at(x, y)[1], image.at(x, y)[2]);
      bool ok = false;
      for (int k = 0; k < 7 && !ok; ++k) {
        glm::vec3 d = dir;
        if (k > 0) d[(k - 1) / 2] += ((k - 1) % 2 == 0 ? 1e-4f : -1e-4f);
        const glm::vec3 expected = gpu::env_radiance(env.view(), env.header(), d);
        ok = glm::all(glm::lessThanEqual(glm::abs(got - expected), 1e-5f * (expected + 1.0f)));
      }
      if (!ok && ++mismatches <= 5) {
        const glm::vec3 e = gpu::env_radiance(env.view(), env.header(), dir);
        ADD_FAILURE() << what << " sky pixel (" << x << ", " << y << ") = (" << got.x << ", "
                      << got.y << ", " << got.z << "), environment along its ray (" << e.x << ", "
                      << e.y << ", " << e.z << ")";
      }
    }
  }
  EXPECT_GT(sky, static_cast<int>(kWidth * kHeight / 3)) << "the camera must see the sky";
  EXPECT_EQ(mismatches, 0) << what;
}

TEST_F(SceneEnvironmentTest, SkyPixelsShowTheEnvironmentAlongTheirRay) {
  Level level =
      env_level("sky.exr", glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.0f, 2.2f, -5.0f), false);
  add_sun(level, 2.0f);
  const lighting::EnvironmentDistribution env =
      lighting::EnvironmentDistribution::load(*level.environment);
  for (const std::string integrator : {"baseline", "reference"}) {
    OfflineRenderRequest request = request_for(integrator, 1);
    request.integrator.spp = integrator == "reference" ? 1u : 0u;
    const auto result = lighting::render_offline(device, shaders, level, request);
    ASSERT_EQ(result.images.size(), 1u);
    EXPECT_EQ(result.images[0].count_non_finite(), 0u);
    expect_sky_is_environment(
        result.images[0], level, env, integrator.c_str());
  }
}

TEST_F(SceneEnvironmentTest, SelectionProbabilityWeighsTheMapAgainstTheEmitters) {
  Level level = env_level("select.exr", glm::vec3(0.0f, 3.0f, 4.0f), glm::vec3(0.0f), true);
  {
    auto no_lights = std::make_shared<const Level>(level);
    const lighting::GpuScene scene(device, no_lights);
    ASSERT_NE(scene.environment_map(), nullptr);
    EXPECT_EQ(scene.environment().params.x, 1.0f) << "only the environment emits";
    EXPECT_EQ(scene.environment().params.z, 1.0f);
  }
  add_sun(level, 3.0f);
  auto lit = std::make_shared<const Level>(level);
  const lighting::GpuScene scene(device, lit);
  const double env_power = scene.environment_map()->power_estimate(scene.scene_radius());
  const double lights_power = scene.data().lights.total_power();
  ASSERT_GT(lights_power, 0.0);
  const double expected = env_power / (env_power + lights_power);
  EXPECT_NEAR(scene.environment().params.x, expected, 1e-6);
  EXPECT_GT(scene.environment().params.x, 0.05f) << "the map must matter in this scene";
  EXPECT_LT(scene.environment().params.x, 0.95f) << "the sun must matter in this scene";

  // Without a map: the black stand-in, never selected.
  Level dark = level;
  dark.environment.reset();
  const lighting::GpuScene none(device, std::make_shared<const Level>(dark));
  EXPECT_EQ(none.environment_map(), nullptr);
  EXPECT_EQ(none.environment().params.x, 0.0f);
  EXPECT_EQ(none.environment().params.z, 0.0f);
  EXPECT_EQ(none.environment().size.z, 0u);
}

double block_mean(const runtime::ImageRGBA32F& image, std::uint32_t x0, std::uint32_t y0,
                  std::uint32_t w, std::uint32_t h) {
  double sum = 0.0;
  for (std::uint32_t y = y0; y < y0 + h; ++y) {
    for (std::uint32_t x = x0; x < x0 + w; ++x) {
      const float* p = image.at(x, y);
      sum += static_cast<double>(p[0]) + p[1] + p[2];
    }
  }
  return sum / (3.0 * w * h);
}

// Looking down at a box on the plane under the map and a sun: every pixel a lit or shadowed
// surface (no sky).
Level converge_level() {
  Level level = env_level("converge.exr", glm::vec3(0.0f, 4.0f, 3.0f), glm::vec3(0.0f), true);
  add_sun(level, 3.0f);
  for (std::uint32_t y = 0; y < kHeight; ++y) {
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      EXPECT_LT(camera_dir(level.camera, x, y).y, 0.0f)
          << "pixel (" << x << ", " << y << ") sees the sky";
    }
  }
  return level;
}

// `image` (the mean of many frames) against the reference: image mean within `mean_tolerance`,
// every 16x12-pixel block within `block_tolerance`.
void expect_converged(const runtime::ImageRGBA32F& ref, const runtime::ImageRGBA32F& image,
                      const char* what, double mean_tolerance, double block_tolerance) {
  EXPECT_EQ(image.count_non_finite(), 0u) << what;
  const double ref_mean = block_mean(ref, 0, 0, kWidth, kHeight);
  const double mean = block_mean(image, 0, 0, kWidth, kHeight);
  std::printf("%s / reference image mean: %.5f (reference %.5f)\n", what, mean / ref_mean,
              ref_mean);
  ASSERT_GT(ref_mean, 0.0);
  EXPECT_NEAR(mean / ref_mean, 1.0, mean_tolerance) << what;
  double worst = 0.0;
  for (std::uint32_t by = 0; by < kHeight; by += 12) {
    for (std::uint32_t bx = 0; bx < kWidth; bx += 16) {
      const double r = block_mean(ref, bx, by, 16, 12);
      const double b = block_mean(image, bx, by, 16, 12);
      ASSERT_GT(r, 0.0);
      worst = std::max(worst, std::abs(b / r - 1.0));
      EXPECT_NEAR(b / r, 1.0, block_tolerance) << what << " block at (" << bx << ", " << by << ")";
    }
  }
  std::printf("%s: worst 16x12 block |image / reference - 1|: %.4f\n", what, worst);
}

class SceneEnvironmentConvergenceTest : public SceneEnvironmentTest {
 protected:
  const runtime::ImageRGBA32F& reference() {
    if (reference_.width == 0) {
      OfflineRenderRequest request = request_for("reference", 4);
      request.integrator.spp = 128;
      request.average = true;
      auto result = lighting::render_offline(device, shaders, level_, request);
      EXPECT_EQ(result.images.size(), 1u);
      EXPECT_EQ(result.images.at(0).count_non_finite(), 0u);
      reference_ = std::move(result.images.at(0));
    }
    return reference_;
  }
  runtime::ImageRGBA32F average(OfflineRenderRequest request) {
    request.average = true;
    auto result = lighting::render_offline(device, shaders, level_, request);
    EXPECT_EQ(result.images.size(), 1u);
    return std::move(result.images.at(0));
  }
  Level level_ = converge_level();
  runtime::ImageRGBA32F reference_;
};

TEST_F(SceneEnvironmentConvergenceTest, BaselineConvergesToReference) {
  OfflineRenderRequest baseline = request_for("baseline", 512);
  baseline.seed = 11;
  expect_converged(reference(), average(baseline), "baseline", 0.01, 0.04);
}

// ReSTIR samples the map as a light (kEnvironmentLight candidates from the light strategy and from
// BSDF rays that escape) and reuses those samples in time and space: the mean of 64 frames of a
// static camera converges to the reference in the unbiased modes, with and without BSDF
// candidates (tolerances: the 3% lit-surface bias bound of the cornell_lights ReSTIR tests, and
// 8% per block for the correlated temporal noise of 64 frames).
TEST_F(SceneEnvironmentConvergenceTest, RestirSamplesTheEnvironmentAndConverges) {
  struct Case {
    const char* name;
    std::vector<std::pair<std::string, std::string>> settings;
  };
  const std::vector<Case> cases = {
      {"restir balance", {{"bias_correction", "balance"}}},
      {"restir pairwise", {{"bias_correction", "pairwise"}}},
      {"restir balance + bsdf candidates",
       {{"bias_correction", "balance"}, {"bsdf_candidates", "1"}}},
  };
  for (const Case& c : cases) {
    OfflineRenderRequest restir = request_for("restir", 64);
    restir.integrator.settings = c.settings;
    restir.seed = 5;
    expect_converged(reference(), average(restir), c.name, 0.03, 0.08);
  }
}

// Synchronisation validation on: a fresh device (the fixture's has plain validation).
class SceneEnvironmentSyncTest : public ::testing::Test {
 protected:
  static runtime::DeviceOptions options() {
    runtime::DeviceOptions o = runtime::test::test_device_options();
    o.sync_validation = true;
    return o;
  }
  void TearDown() override {
    EXPECT_TRUE(device.sync_validation_enabled()) << "synchronisation validation unavailable";
    EXPECT_EQ(device.validation_errors(), 0u);
  }
  runtime::Device device{options()};
  runtime::ShaderLibrary shaders;
};

void render_under_sync_validation(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                  const std::string& integrator) {
  Level level =
      env_level("sync.exr", glm::vec3(0.0f, 1.5f, 4.0f), glm::vec3(0.0f, 0.8f, 0.0f), true);
  add_sun(level, 3.0f);
  OfflineRenderRequest request = request_for(integrator, 3);
  request.integrator.spp = integrator == "reference" ? 2u : 0u;
  request.animate = true;
  const auto result = lighting::render_offline(device, shaders, level, request);
  ASSERT_EQ(result.images.size(), 3u);
  for (const auto& image : result.images) EXPECT_EQ(image.count_non_finite(), 0u);
}

TEST_F(SceneEnvironmentSyncTest, BaselineAndReferenceFramesHaveNoHazard) {
  render_under_sync_validation(device, shaders, "baseline");
  render_under_sync_validation(device, shaders, "reference");
}

TEST_F(SceneEnvironmentSyncTest, RestirFramesHaveNoHazard) {
  render_under_sync_validation(device, shaders, "restir");
}

}  // namespace
}  // namespace lantern
