// Validation flythrough (gpu): every level in content/levels/ flown along its camera path (the
// level's default path, else its first one; static camera if it has none) with baseline and
// restir, on a device with the validation layer AND synchronization validation on. Asserts zero
// validation errors (sync hazards are errors), sync validation really enabled, and every frame
// finite.
//
// ctest: 30 frames at 64x36 (million_lights: 8). The long run (issue 7: 1,000 frames per level) is the same test with
//   LANTERN_FLYTHROUGH_FRAMES=1000 build/bin/validation_flythrough_test
// (scripts/validate_flythrough.sh runs it per level and prints the counts and times).
// LANTERN_FLYTHROUGH_SIZE=WxH changes the size.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/level/level_loader.h"
#include "engine/world/world.h"
#include "lighting/frame/headless_session.h"
#include "runtime/core/device.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/image/image.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {


std::vector<std::string> level_names() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(content_dir() / "levels")) {
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::uint32_t env_uint(const char* name, std::uint32_t fallback) {
  const char* v = std::getenv(name);
  return v ? static_cast<std::uint32_t>(std::stoul(v)) : fallback;
}

struct Size {
  std::uint32_t width = 64;
  std::uint32_t height = 36;
};

Size flythrough_size() {
  Size s;
  if (const char* v = std::getenv("LANTERN_FLYTHROUGH_SIZE")) {
    if (std::sscanf(v, "%ux%u", &s.width, &s.height) != 2 || s.width == 0 || s.height == 0)
      throw InputError(std::string("LANTERN_FLYTHROUGH_SIZE: expected WxH, got ") + v);
  }
  return s;
}

struct Case {
  std::string level;
  std::string integrator;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.level << " " << c.integrator;
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const std::string& level : level_names()) {
    out.push_back({level, "baseline"});
    out.push_back({level, "restir"});
  }
  return out;
}

runtime::DeviceOptions sync_validated_options() {
  runtime::DeviceOptions options = runtime::test::test_device_options();
  options.validation = true;
  options.sync_validation = true;
  return options;
}

class ValidationFlythrough : public ::testing::TestWithParam<Case> {
 protected:
  runtime::Device device{sync_validated_options()};
  runtime::ShaderLibrary shaders;
};

TEST_P(ValidationFlythrough, ZeroValidationErrors) {
  using clock = std::chrono::steady_clock;
  const Case& c = GetParam();
  ASSERT_TRUE(device.validation_enabled()) << "validation layer unavailable";
  ASSERT_TRUE(device.sync_validation_enabled()) << "synchronization validation unavailable";
  // million_lights costs ~0.25 s a frame on lavapipe: 8 frames keep its short run under 20 s.
  const std::uint32_t frames =
      env_uint("LANTERN_FLYTHROUGH_FRAMES", c.level == "million_lights" ? 8 : 30);
  const Size size = flythrough_size();

  const auto t0 = clock::now();
  Level loaded = load_level_argument(c.level);
  if (loaded.camera_path.empty() && !loaded.paths.empty()) loaded.camera_path = loaded.paths[0].name;
  const std::string path = loaded.camera_path.empty() ? "(static)" : loaded.camera_path;
  const auto level = std::make_shared<const Level>(std::move(loaded));
  lighting::HeadlessSession session(
      device, shaders, level,
      {.integrator = {.name = c.integrator}, .width = size.width, .height = size.height});
  session.warm_up();
  const auto t1 = clock::now();

  std::uint32_t non_finite_frames = 0;
  double gpu_ms = 0.0;
  runtime::ImageRGBA32F image;
  for (std::uint32_t f = 0; f < frames; ++f) {
    const FrameSnapshot& snapshot = session.step_world();
    gpu_ms += session.render(snapshot, &image).gpu_ms;
    if (image.count_non_finite() != 0) ++non_finite_frames;
  }
  const auto t2 = clock::now();
  const double setup_s = std::chrono::duration<double>(t1 - t0).count();
  const double run_s = std::chrono::duration<double>(t2 - t1).count();
  std::printf(
      "[flythrough] %s %s path %s: %u frames at %ux%u, validation errors %u, warnings %u, "
      "performance warnings %u, non-finite frames %u; load+warm-up %.1f s, frames %.1f s "
      "(GPU %.1f ms/frame)\n",
      c.level.c_str(), c.integrator.c_str(), path.c_str(), frames, size.width,
      size.height, device.validation_errors(), device.validation_warnings(),
      device.performance_warnings(), non_finite_frames, setup_s, run_s,
      frames ? gpu_ms / frames : 0.0);
  EXPECT_EQ(non_finite_frames, 0u);
  EXPECT_EQ(device.validation_errors(), 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Levels, ValidationFlythrough, ::testing::ValuesIn(cases()),
    [](const ::testing::TestParamInfo<Case>& param_info) {
      return param_info.param.level + "_" + param_info.param.integrator;
    });

}  // namespace
}  // namespace lantern
