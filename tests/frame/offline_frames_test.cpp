// render_offline's frame selection: `first_frame` K renders the world's frame K (the same image
// as the K-th frame of an animated render), animate = false repeats the first rendered frame's
// snapshot, animate = true moves things. The scene is cornell_lights with nothing reflective and
// the moving box emissive, so images are emission only: deterministic, compared exactly.
#include <gtest/gtest.h>

#include "engine/level/level_loader.h"
#include "lighting/integrators/offline_render.h"
#include "runtime/gpu/shader_library.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {

class OfflineFramesTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;
};

std::shared_ptr<const Level> emission_only_cornell() {
  Level level = load_level_argument("cornell_lights");
  for (Material& m : level.materials) {
    m.base_color = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    m.metallic = 0.0f;
    m.specular_factor = 0.0f;
  }
  Material glow;
  glow.name = "test_glow";
  glow.base_color = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  glow.metallic = 0.0f;
  glow.specular_factor = 0.0f;
  glow.emissive_factor = glm::vec3(1.0f, 0.5f, 0.25f);
  glow.emissive_strength = 3.0f;
  level.materials.push_back(glow);
  bool found = false;
  for (Instance& i : level.instances) {
    if (i.name == "moving_box") {
      i.material = static_cast<std::uint32_t>(level.materials.size() - 1);
      found = true;
    }
  }
  EXPECT_TRUE(found);
  return std::make_shared<const Level>(std::move(level));
}

std::size_t differing_pixels(const runtime::ImageRGBA32F& a, const runtime::ImageRGBA32F& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.pixels.size(); i += 4) {
    if (a.pixels[i] != b.pixels[i] || a.pixels[i + 1] != b.pixels[i + 1] ||
        a.pixels[i + 2] != b.pixels[i + 2])
      ++n;
  }
  return n;
}

TEST_F(OfflineFramesTest, FirstFrameAndAnimateBehaveAsDocumented) {
  const auto level = emission_only_cornell();
  constexpr std::uint32_t kSkip = 20;
  lighting::OfflineRenderRequest animated;
  animated.width = 64;
  animated.height = 36;
  animated.frames = kSkip + 1;
  const auto all = lighting::render_offline(device, shaders, level, animated);
  ASSERT_EQ(all.images.size(), kSkip + 1);
  ASSERT_EQ(all.frame_ms.size(), kSkip + 1);
  ASSERT_EQ(all.pass_ms.size(), kSkip + 1);
  EXPECT_GT(all.median_pass_ms("integrators.baseline"), 0.0);
  EXPECT_GT(all.median_pass_ms("scene.upload"), 0.0);
  // The box moved: some pixels changed between frame 0 and frame K.
  EXPECT_GT(differing_pixels(all.images.front(), all.images.back()), 0u);

  // --frame K: the world's frame K, rendered first (a camera cut; emission does not care).
  lighting::OfflineRenderRequest skipped = animated;
  skipped.frames = 3;
  skipped.first_frame = kSkip;
  skipped.animate = false;
  const auto frozen = lighting::render_offline(device, shaders, level, skipped);
  ASSERT_EQ(frozen.images.size(), 3u);
  EXPECT_EQ(differing_pixels(frozen.images[0], all.images.back()), 0u);
  // animate = false: every frame is the same snapshot.
  EXPECT_EQ(differing_pixels(frozen.images[0], frozen.images[1]), 0u);
  EXPECT_EQ(differing_pixels(frozen.images[0], frozen.images[2]), 0u);
  for (const auto& image : frozen.images) EXPECT_EQ(image.count_non_finite(), 0u);
}

}  // namespace
}  // namespace lantern
