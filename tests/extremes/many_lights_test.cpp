// Many emitters (gpu): the light_field generator (content/levels/million_lights.json's content)
// at 10^6 emissive triangles (measured ~8 s for both integrators on lavapipe: generation 0.1 s,
// scene build + warm-up + 2 frames 3.6 s baseline, 4.2 s restir); LANTERN_EXTREMES_EMITTERS=N
// for another count. Two frames at 48x27: no crash, no NaN/Inf pixel, a lit image, zero
// validation errors. No reference comparison: a converged
// reference of this scene at ctest cost is not available; the same-seed restir/baseline means
// are printed.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "engine/level/generators/light_field.h"
#include "runtime/gpu/shader_library.h"
#include "tests/extremes/extremes_support.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern::extremes {
namespace {

std::uint32_t emitter_triangles() {
  if (const char* env = std::getenv("LANTERN_EXTREMES_EMITTERS")) {
    return static_cast<std::uint32_t>(std::stoul(env));
  }
  return 1000000;
}

class ManyLightsTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;
};

TEST_F(ManyLightsTest, LightFieldRendersFiniteWithBaselineAndRestir) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  auto level = std::make_shared<Level>();
  level->name = "light_field";
  LoadDiagnostics diagnostics;
  LevelBuilder builder(*level, diagnostics);
  LightFieldParams params;
  params.seed = 11;  // as content/levels/million_lights.json
  params.emitter_triangles = emitter_triangles();
  generate_light_field(params, builder, "extremes light_field");
  level->camera_path.clear();  // the path's first pose, held still
  const double generate_s = std::chrono::duration<double>(clock::now() - t0).count();

  for (const IntegratorConfig& config : {baseline(), restir()}) {
    const auto t1 = clock::now();
    const std::vector<runtime::ImageRGBA32F> frames =
        render_static(device, shaders, *level, config, 2, false, 48, 27);
    const double render_s = std::chrono::duration<double>(clock::now() - t1).count();
    ASSERT_EQ(frames.size(), 2u);
    for (const runtime::ImageRGBA32F& image : frames) {
      EXPECT_EQ(image.count_non_finite(), 0u) << name_of(config);
      EXPECT_GE(min_channel(image), 0.0) << name_of(config);
      EXPECT_GT(runtime::mean_rgb(image), 0.0) << name_of(config) << ": the field lights the floor";
    }
    std::printf(
        "[extremes] light_field %u emitter triangles %s: generate %.1f s, 2 frames at 48x27 "
        "(scene build + warm-up + render) %.1f s, mean %.5g\n",
        params.emitter_triangles, name_of(config), generate_s, render_s,
        runtime::mean_rgb(frames[1]));
  }
}

}  // namespace
}  // namespace lantern::extremes
