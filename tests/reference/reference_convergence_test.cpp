// The reference as a yardstick: (c) the baseline integrator (1 sample per pixel per frame, light
// sampling only) converges to the reference on cornell_lights — the mean of many baseline frames
// is within 1% of the reference's image mean, and on lit surfaces alone — and the reference cache
// (reference_cache.h): a second request is a cache hit returning the same pixels, and every key
// input changes the name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/level/level_loader.h"
#include "lighting/integrators/offline_render.h"
#include "lighting/integrators/reference_cache.h"
#include "runtime/gpu/shader_library.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {

class ReferenceConvergenceTest : public runtime::test::GpuTest {
 protected:
  void SetUp() override {
    // A cache of this test run only: the first request renders, the second must hit.
    cache_dir_ = std::filesystem::temp_directory_path() /
                 ("lantern_reference_cache_test_" + std::to_string(::getpid()));
    std::filesystem::remove_all(cache_dir_);
    ::setenv("LANTERN_CACHE_DIR", cache_dir_.c_str(), 1);
  }
  void TearDown() override {
    ::unsetenv("LANTERN_CACHE_DIR");
    std::filesystem::remove_all(cache_dir_);
    GpuTest::TearDown();
  }
  runtime::ShaderLibrary shaders;
  std::filesystem::path cache_dir_;
};

double image_mean(const runtime::ImageRGBA32F& image) {
  double sum = 0.0;
  for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
    sum += image.pixels[i] + image.pixels[i + 1] + image.pixels[i + 2];
  }
  return sum / (3.0 * static_cast<double>(image.width) * image.height);
}

TEST_F(ReferenceConvergenceTest, BaselineMeanConvergesToReferenceOnCornellLights) {
  auto level = std::make_shared<const Level>(load_level_argument("cornell_lights"));
  lighting::ReferenceRequest request;
  request.width = 64;
  request.height = 36;
  request.spp = 256;
  request.frames = 4;
  const lighting::ReferenceImage reference =
      lighting::reference_image(device, shaders, level, request);
  EXPECT_FALSE(reference.cache_hit);
  ASSERT_EQ(reference.image.width, 64u);
  EXPECT_EQ(reference.image.count_non_finite(), 0u);
  EXPECT_TRUE(std::filesystem::exists(reference.path)) << reference.path;

  // Second request: from the cache, bit-identical (EXR float32 round trip).
  const lighting::ReferenceImage again = lighting::reference_image(device, shaders, level, request);
  EXPECT_TRUE(again.cache_hit);
  EXPECT_EQ(again.image.pixels, reference.image.pixels);

  lighting::OfflineRenderRequest baseline;
  baseline.integrator.name = "baseline";
  baseline.width = request.width;
  baseline.height = request.height;
  baseline.frames = 1024;
  baseline.average = true;
  baseline.animate = false;
  baseline.seed = 7;
  const auto result = lighting::render_offline(device, shaders, level, baseline);
  ASSERT_EQ(result.images.size(), 1u);
  EXPECT_EQ(result.images[0].count_non_finite(), 0u);
  const double reference_mean = image_mean(reference.image);
  const double baseline_mean = image_mean(result.images[0]);
  std::printf(
      "cornell_lights 64x36: reference mean %.6g (1024 spp), baseline mean %.6g (1024 "
      "frames), ratio %.5f\n",
      reference_mean, baseline_mean, baseline_mean / reference_mean);
  ASSERT_GT(reference_mean, 0.0);
  EXPECT_NEAR(baseline_mean / reference_mean, 1.0, 0.01);

  // Directly seen emitters are identical in both images and dominate the mean: compare again on
  // the pixels below the reference's 80th percentile (chosen from the reference alone, so the
  // baseline's noise cannot bias the selection), i.e. lit surfaces.
  std::vector<float> values;
  for (std::size_t i = 0; i < reference.image.pixels.size(); i += 4) {
    values.push_back(reference.image.pixels[i] + reference.image.pixels[i + 1] +
                     reference.image.pixels[i + 2]);
  }
  std::vector<float> sorted = values;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() * 8 / 10, sorted.end());
  const float cut = sorted[sorted.size() * 8 / 10];
  double ref_sum = 0.0;
  double base_sum = 0.0;
  for (std::size_t p = 0; p < values.size(); ++p) {
    if (values[p] >= cut) continue;
    ref_sum += values[p];
    base_sum += result.images[0].pixels[4 * p] + result.images[0].pixels[4 * p + 1] +
                result.images[0].pixels[4 * p + 2];
  }
  std::printf("lit surfaces (below the 80th percentile): baseline / reference %.5f\n",
              base_sum / ref_sum);
  ASSERT_GT(ref_sum, 0.0);
  EXPECT_NEAR(base_sum / ref_sum, 1.0, 0.01);
}

// A reference renders the world of the run it is measured against: its samples have a seed of
// their own, its world (the flickering light's power, frame by frame) the run's. flicker_box's
// light moves between 0 and 1x twice a second at random by the world's seed: with the run's world
// seed the reference's image mean matches the run's world rendered by the reference itself with
// the run's seed (to its noise, 0.5%), while a reference of another world seed is far off (> 10%
// at this frame; `lantern trade` compared such references with its rows until the world seed
// was passed: night_market's flickering lights).
TEST_F(ReferenceConvergenceTest, ReferenceShowsTheWorldOfTheMeasuredRun) {
  auto level = std::make_shared<const Level>(
      load_level_argument(std::string(LANTERN_SOURCE_DIR) + "/content/studies/flicker_box.json"));
  lighting::ReferenceRequest request;
  request.width = 48;
  request.height = 27;
  request.frame = 5;
  request.spp = 64;
  request.frames = 4;
  request.seed = 1;  // the run's own world and samples
  const double run_world =
      image_mean(lighting::reference_image(device, shaders, level, request).image);
  request.seed = 1001;  // other samples, the run's world
  request.world_seed = 1;
  const double same_world =
      image_mean(lighting::reference_image(device, shaders, level, request).image);
  request.world_seed.reset();  // other samples and another world
  const double other_world =
      image_mean(lighting::reference_image(device, shaders, level, request).image);
  ASSERT_GT(run_world, 0.0);
  EXPECT_NEAR(same_world / run_world, 1.0, 0.005);
  EXPECT_GT(std::abs(other_world / run_world - 1.0), 0.1);
}

TEST(ReferenceCacheKey, EveryInputChangesTheName) {
  Level level;
  level.name = "key test";
  lighting::ReferenceRequest request;
  const std::string base = lighting::reference_cache_name(level, request);
  EXPECT_NE(base.find("key_test-320x180-f0-"), std::string::npos) << base;
  EXPECT_EQ(base.substr(base.size() - 4), ".exr");
  EXPECT_EQ(lighting::reference_cache_name(level, request), base) << "deterministic";
  auto changed = [&](auto mutate) {
    Level l = level;
    lighting::ReferenceRequest r = request;
    mutate(l, r);
    return lighting::reference_cache_name(l, r);
  };
  EXPECT_NE(changed([](Level&, lighting::ReferenceRequest& r) { r.width = 321; }), base);
  EXPECT_NE(changed([](Level&, lighting::ReferenceRequest& r) { r.frame = 3; }), base);
  EXPECT_NE(changed([](Level&, lighting::ReferenceRequest& r) { r.spp = 65; }), base);
  EXPECT_NE(changed([](Level&, lighting::ReferenceRequest& r) { r.frames = 17; }), base);
  EXPECT_NE(changed([](Level&, lighting::ReferenceRequest& r) { r.seed = 2; }), base);
  EXPECT_NE(changed([](Level&, lighting::ReferenceRequest& r) { r.world_seed = 2; }), base);
  EXPECT_EQ(changed([](Level&, lighting::ReferenceRequest& r) { r.world_seed = r.seed; }), base)
      << "a world seed equal to the samples' seed is the same world";
  EXPECT_NE(changed([](Level&, lighting::ReferenceRequest& r) {
              r.settings.emplace_back("reference.spp", "8");
            }),
            base);
  EXPECT_NE(changed([](Level& l, lighting::ReferenceRequest&) { l.camera.yfov = 0.7f; }), base);
  EXPECT_NE(changed([](Level& l, lighting::ReferenceRequest&) {
              Light light;
              l.lights.push_back(light);
            }),
            base);
  EXPECT_NE(changed([](Level& l, lighting::ReferenceRequest&) { l.source = "other.json"; }), base);
}

}  // namespace
}  // namespace lantern
