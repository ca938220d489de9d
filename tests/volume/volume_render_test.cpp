// Media on the GPU (issue 14): transmittance along camera and shadow rays for every integrator.
// A floor under a point light inside a large absorbing fog (scattering 0, so no light is
// in-scattered and the closed form is Beer-Lambert on both legs): each pixel is the fog-free
// image's value times exp(-sigma_a (|camera - p| + |light - p|)), p the floor point the pixel
// sees (the fog box reaches 5 m beyond every path, so every cell on them is homogeneous and the
// residual ratio tracking estimate is exact). A zero-density volume renders bit for bit as the
// level without it. The fog-free image is the renderer's own: this isolates the media. A moving
// volume's record carries its motion.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/glm.hpp>
#include <string>

#include "engine/level/level_loader.h"
#include "engine/world/world.h"
#include "lighting/scene/gpu_scene.h"
#include "runtime/gpu/shader_library.h"
#include "tests/restir/restir_test_support.h"
#include "tests/runtime/gpu_test_support.h"
#include "tests/volume/volume_render_support.h"

namespace lantern {
namespace {

constexpr std::uint32_t kWidth = 64;
constexpr std::uint32_t kHeight = 36;
constexpr double kSigmaA = 0.15;  // 1/m
// The level, with a volume entry (`volume` JSON text) or none.
std::string level_json(const std::string& volume) {
  return test::with_volume(test::kFloorUnderPointLight, volume);
}

std::string fog(double density_scale) {
  return R"({ "name": "fog", "generate": { "type": "constant", "size": [40, 20, 40], "voxel_size": 0.5 },
    "translation": [0, -5, 0], "density_scale": )" +
         std::to_string(density_scale) + R"(, "scattering": [0, 0, 0], "absorption": [)" +
         std::to_string(kSigmaA) + ", " + std::to_string(kSigmaA) + ", " + std::to_string(kSigmaA) +
         "] }";
}

class VolumeRenderTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;

  runtime::ImageRGBA32F render(const Level& level, const std::string& integrator) {
    return test::render_volume_level(device, shaders, level, integrator,
                                     {.width = kWidth, .height = kHeight});
  }
};

TEST_F(VolumeRenderTest, AbsorbingFogIsBeerLambertOnCameraAndShadowRays) {
  const auto clear = test::level_from_json("volume_clear", level_json(""));
  const auto foggy = test::level_from_json("volume_fog", level_json(fog(1.0)));
  ASSERT_EQ(foggy->volumes.size(), 1u);
  for (const char* integrator : {"baseline", "restir", "reference"}) {
    const runtime::ImageRGBA32F a = render(*clear, integrator);
    const runtime::ImageRGBA32F b = render(*foggy, integrator);
    double worst = 0.0, mean_ratio = 0.0;
    std::size_t n = 0;
    for (std::uint32_t y = 0; y < kHeight; ++y)
      for (std::uint32_t x = 0; x < kWidth; ++x) {
        const glm::dvec3 p = test::floor_point(*clear, kWidth, kHeight, x, y);
        ASSERT_LT(std::max(std::abs(p.x), std::abs(p.z)), 3.0) << "the floor fills the view";
        const double t = std::exp(-kSigmaA * (glm::length(test::kFloorCamera - p) + glm::length(test::kFloorLight - p)));
        const std::size_t i = 4 * (std::size_t{y} * kWidth + x);
        for (int k = 0; k < 3; ++k) {
          const double clear_value = a.pixels[i + static_cast<std::size_t>(k)];
          if (!(clear_value > 0.0)) continue;
          const double ratio = b.pixels[i + static_cast<std::size_t>(k)] / clear_value;
          worst = std::max(worst, std::abs(ratio / t - 1.0));
          mean_ratio += ratio / t;
          ++n;
        }
      }
    std::printf("[volume] %s: absorbing fog / clear vs Beer-Lambert: mean %.6f, worst pixel %.2e\n",
                integrator, mean_ratio / double(n), worst);
    EXPECT_GT(n, std::size_t{kWidth} * kHeight * 2);
    // Baseline and ReSTIR shade one deterministic point-light sample per pixel: per pixel. The
    // reference's own noise cancels in the ratio only up to its BSDF samples' share (none reach
    // a point light, so the ratio is exact there too).
    EXPECT_LE(worst, 2e-3) << integrator;
  }
}

TEST_F(VolumeRenderTest, ZeroDensityVolumeRendersExactlyAsWithout) {
  const auto clear = test::level_from_json("volume_clear0", level_json(""));
  const auto empty = test::level_from_json("volume_zero", level_json(fog(0.0)));
  for (const char* integrator : {"baseline", "restir", "reference"}) {
    const runtime::ImageRGBA32F a = render(*clear, integrator);
    const runtime::ImageRGBA32F b = render(*empty, integrator);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
      differing += std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) != 0 ? 1 : 0;
    EXPECT_EQ(differing, 0u) << integrator;
  }
}

// The GPU record of a moving volume carries its motion since last frame (what the media
// reservoirs' temporal shift follows): the circling plume's maps last frame's world points to
// this frame's, the still fog bank's is the identity, and a frozen snapshot makes both still.
TEST_F(VolumeRenderTest, MovingVolumeRecordsCarryTheirMotion) {
  const auto level = std::make_shared<const Level>(load_level_argument("smoke_yard"));
  World world(level, {.threads = 2});
  const FrameSnapshot first = world.step();
  const FrameSnapshot second = world.step();
  lighting::GpuScene scene(device, level);
  scene.update(second);
  const gpu::GpuVolume& fog = scene.data().volumes[0];
  const gpu::GpuVolume& plume = scene.data().volumes[1];
  EXPECT_EQ(fog.motion, glm::mat4(1.0f));
  EXPECT_NE(plume.motion, glm::mat4(1.0f));
  for (const glm::vec4 p : {glm::vec4(0, 0, 0, 1), glm::vec4(3, 1, -2, 1), glm::vec4(-1, 4, 5, 1)}) {
    // The same point of the plume (index space) last frame and now.
    const glm::vec4 before = first.volumes[1].object_to_world * p;
    const glm::vec4 now = second.volumes[1].object_to_world * p;
    const glm::vec4 moved = plume.motion * before;
    const glm::vec4 back = plume.motion_inverse * now;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(moved[c], now[c], 1e-4f);
      EXPECT_NEAR(back[c], before[c], 1e-4f);
    }
  }
  scene.update(frozen(second));
  EXPECT_EQ(scene.data().volumes[1].motion, glm::mat4(1.0f));
  EXPECT_EQ(scene.data().volumes[1].motion_inverse, glm::mat4(1.0f));
}

}  // namespace
}  // namespace lantern
