// Integrators made from the registry on lavapipe, and their settings through the Integrator
// interface (describe_settings / apply_settings: what play uses, no cast to a technique's type).
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "engine/core/error.h"
#include "lighting/integrators/integrator_registry.h"
#include "runtime/image/image_metrics.h"
#include "tests/restir/restir_test_support.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {

using lighting::IntegratorConfig;
using lighting::IntegratorEntry;
using runtime::ImageRGBA32F;
using test::RenderHarness;
using Settings = std::vector<std::pair<std::string, std::string>>;

constexpr std::uint32_t kW = 96;
constexpr std::uint32_t kH = 54;

class IntegratorSettingsTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;
  std::shared_ptr<const Level> level =
      std::make_shared<const Level>(load_level_argument("cornell_lights"));
};

// Every row: made by the registry, it renders a lit, finite frame; applying its own description
// back changes nothing; an unknown key is refused and leaves its settings as they were.
TEST_F(IntegratorSettingsTest, EveryIntegratorRendersAndTakesItsOwnSettingsBack) {
  const FrameSnapshot first = test::first_snapshot(level, kW, kH);
  for (const IntegratorEntry& entry : lighting::integrators()) {
    IntegratorConfig config{.name = entry.name};
    if (entry.name == std::string("reference")) config.spp = 2;  // a quick frame
    RenderHarness h(device, shaders, level, lighting::make_integrator(device, shaders, config), kW,
                    kH);
    const ImageRGBA32F image = h.render(first);
    EXPECT_TRUE(test::all_finite(image)) << entry.name;
    EXPECT_GT(runtime::mean_rgb(image), 0.0) << entry.name;

    const Settings described = h.integrator().describe_settings();
    EXPECT_NO_THROW(h.integrator().apply_settings(described)) << entry.name;
    EXPECT_EQ(h.integrator().describe_settings(), described) << entry.name;
    EXPECT_THROW(h.integrator().apply_settings({{"no_such_key", "1"}}), InputError) << entry.name;
    EXPECT_EQ(h.integrator().describe_settings(), described) << entry.name;
  }
}

std::string value_of(const Settings& settings, const std::string& key) {
  for (const auto& [k, v] : settings)
    if (k == key) return v;
  return "";
}

// Play's path: a ReSTIR setting changed on the running integrator takes effect next frame. The
// debug view changes only what restir.shade writes, so after the change the frame equals, bit for
// bit, the one an integrator made with that view from the start renders (same seed, same
// reservoirs). A change with one bad value is refused whole.
TEST_F(IntegratorSettingsTest, LiveRestirChangeEqualsAFreshIntegrator) {
  RenderHarness live(device, shaders, level, test::make_restir(device, shaders, {}), kW, kH);
  RenderHarness fresh(device, shaders, level,
                      test::make_restir(device, shaders, {{"debug_view", "w"}}), kW, kH);
  FrameSnapshot s = test::first_snapshot(level, kW, kH);
  const ImageRGBA32F radiance = live.render(s);
  (void)fresh.render(s);

  EXPECT_THROW(live.integrator().apply_settings({{"debug_view", "w"}, {"radius", "-1"}}),
               InputError);
  EXPECT_EQ(value_of(live.integrator().describe_settings(), "debug_view"), "none")
      << "a refused change changes nothing";
  live.integrator().apply_settings({{"debug_view", "w"}});
  EXPECT_EQ(value_of(live.integrator().describe_settings(), "debug_view"), "w");

  s = frozen(s);
  const ImageRGBA32F changed = live.render(s);
  const ImageRGBA32F expected = fresh.render(s);
  EXPECT_EQ(changed.pixels, expected.pixels) << "the live change differs from a fresh integrator";
  EXPECT_NE(changed.pixels, radiance.pixels) << "the W view looks like radiance: no change seen";
}

}  // namespace
}  // namespace lantern
