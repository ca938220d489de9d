// FrameRenderer on a running World: frames along cornell_lights' camera path are finite and lit
// with no validation error; a moving instance's GpuInstance (read back from the device) carries
// last frame's transform as its previous one; a light removed from the snapshot maps to
// kInvalidLight in the prev->current remap and its contribution leaves the image; a flicker
// rewrites (and uploads) only the analytic lights' alias table, and the device's table is the
// CPU's.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>

#include "engine/level/level_loader.h"
#include "engine/level/primitives.h"
#include "engine/world/world.h"
#include "lighting/scene/frame_constants.h"
#include "lighting/scene/scene_data.h"
#include "runtime/gpu/transfer.h"
#include "shared/color.h"
#include "shared/common_math.h"
#include "shared/lights.h"
#include "shared/scene.h"
#include "tests/frame/frame_harness.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {

class FrameRendererTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;
};

double mean_luminance(const runtime::ImageRGBA32F& image) {
  double sum = 0.0;
  for (std::uint32_t y = 0; y < image.height; ++y)
    for (std::uint32_t x = 0; x < image.width; ++x) {
      const float* p = image.at(x, y);
      sum += gpu::luminance(glm::vec3(p[0], p[1], p[2]));
    }
  return sum / (double(image.width) * image.height);
}

TEST_F(FrameRendererTest, CornellLightsAlongTheCameraPathIsFiniteAndLit) {
  auto level = std::make_shared<const Level>(load_level_argument("cornell_lights"));
  World world(level, {.threads = 1, .seed = 3, .fixed_dt = 1.0 / 10.0, .aspect = 16.0f / 9.0f});
  world.set_camera_path("dolly");
  test::FrameHarness harness(device, shaders, level, 160, 90);
  glm::vec3 first_position{0.0f};
  for (int frame = 0; frame < 4; ++frame) {
    const FrameSnapshot& snapshot = world.step();
    if (frame == 0) first_position = snapshot.camera.position;
    const runtime::ImageRGBA32F image = harness.render(snapshot);
    EXPECT_EQ(image.count_non_finite(), 0u) << "frame " << frame;
    EXPECT_GT(mean_luminance(image), 0.0) << "frame " << frame;
    const auto& inputs = harness.renderer().last_inputs();
    EXPECT_EQ(harness.renderer().history_valid(), frame > 0) << "frame " << frame;
    EXPECT_EQ(inputs.frame_index, static_cast<std::uint32_t>(frame));
    if (frame == 3) {
      EXPECT_GT(glm::length(snapshot.camera.position - first_position), 1e-3f)
          << "the camera did not move along the path: the test proves little";
    }
  }
}

// With a timing interval of 3 the session times frames 0, 3, 6 (their GPU times come back, the
// others' do not) and renders the same images as when it times every frame (play times one in 8:
// a pass's timestamps cost lavapipe ~60 us of wall time).
TEST_F(FrameRendererTest, TimingIntervalTimesOneFrameInN) {
  auto level = std::make_shared<const Level>(load_level_argument("cornell_lights"));
  World world(level, {.threads = 1, .seed = 3, .fixed_dt = 1.0 / 10.0, .aspect = 16.0f / 9.0f});
  test::FrameHarness every(device, shaders, level, 64, 36);
  test::FrameHarness third(device, shaders, level, 64, 36);
  third.session().set_timing_interval(3);
  for (int frame = 0; frame < 7; ++frame) {
    const FrameSnapshot& snapshot = world.step();
    lighting::FrameTiming timing;
    ASSERT_TRUE(third.session().render(snapshot, {}, &timing));
    EXPECT_EQ(timing.gpu_valid, frame % 3 == 0) << "frame " << frame;
    EXPECT_EQ(timing.passes.empty(), frame % 3 != 0) << "frame " << frame;
    if (frame % 3 == 0) {
      EXPECT_GT(timing.gpu_ms, 0.0) << "frame " << frame;
    }
    const runtime::ImageRGBA32F timed = every.render(snapshot);
    const runtime::ImageRGBA32F image = third.output();
    std::size_t differ = 0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
      differ += image.pixels[i] != timed.pixels[i];
    }
    EXPECT_EQ(differ, 0u) << "frame " << frame;
  }
}

TEST_F(FrameRendererTest, MovingInstanceCarriesLastFramesTransformAsPrevious) {
  auto level = std::make_shared<const Level>(load_level_argument("cornell_lights"));
  std::uint32_t moving = 0;
  for (std::uint32_t i = 0; i < level->instances.size(); ++i)
    if (level->instances[i].name == "moving_box") moving = i;
  ASSERT_TRUE(level->instances[moving].behaviour.has_value());
  World world(level, {.threads = 1, .seed = 1, .fixed_dt = 1.0 / 10.0, .aspect = 16.0f / 9.0f});
  test::FrameHarness harness(device, shaders, level, 64, 36);
  glm::mat4 last{1.0f};
  for (int frame = 0; frame < 3; ++frame) {
    const FrameSnapshot& snapshot = world.step();
    const SnapshotInstance* s = nullptr;
    for (const SnapshotInstance& i : snapshot.instances)
      if (i.stable_id == moving) s = &i;
    ASSERT_NE(s, nullptr);
    harness.render(snapshot);
    const auto& scene = harness.renderer().scene();
    const std::vector<gpu::GpuInstance> gpu = runtime::read_buffer<gpu::GpuInstance>(
        device, scene.device_buffer(gpu::kSceneInstances));
    ASSERT_GT(gpu.size(), moving);
    EXPECT_EQ(gpu[moving].object_to_world, s->object_to_world) << "frame " << frame;
    if (frame > 0) {
      EXPECT_EQ(gpu[moving].prev_object_to_world, last) << "frame " << frame;
      EXPECT_NE(gpu[moving].object_to_world, last) << "the box did not move";
      EXPECT_TRUE(scene.last_update().tlas_rebuilt);
    }
    last = s->object_to_world;
  }
}

// A Lambertian plane under two point lights; the camera looks straight down at the origin.
Level two_light_level() {
  Level level;
  level.name = "two_lights";
  level.meshes.push_back(make_plane(glm::vec2(20.0f, 20.0f)));
  Material m;
  m.base_color = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.specular_factor = 0.0f;
  level.materials.push_back(m);
  Instance inst;
  inst.name = "plane";
  level.instances.push_back(inst);
  for (int k = 0; k < 2; ++k) {
    Light light;
    light.name = k == 0 ? "kept" : "removed";
    light.type = LightType::Point;
    light.intensity = k == 0 ? 10.0f : 40.0f;
    light.position = glm::vec3(k == 0 ? 0.0f : 1.5f, 2.0f, 0.0f);
    level.lights.push_back(light);
  }
  level.camera.position = glm::vec3(0.0f, 4.0f, 0.0f);
  level.camera.orientation = look_at_orientation(level.camera.position, glm::vec3(0.0f));
  level.camera.yfov = 0.6f;
  level.has_camera = true;
  return level;
}

TEST_F(FrameRendererTest, RemovedLightMapsToInvalidAndLeavesTheImage) {
  auto level = std::make_shared<const Level>(two_light_level());
  World world(level, {.threads = 1, .seed = 1, .fixed_dt = 1.0 / 60.0, .aspect = 41.0f / 31.0f});
  test::FrameHarness harness(device, shaders, level, 41, 31);
  const FrameSnapshot& first = world.step();
  ASSERT_EQ(first.lights.size(), 2u);
  const FrameSnapshot both = first;
  harness.render(both);
  const auto& scene = harness.renderer().scene();
  ASSERT_EQ(scene.light_record_count(), 2u);
  EXPECT_EQ(scene.data().lights.stable_ids()[1], lighting::kAnalyticLightIdBase | 1u);
  // Every light kept its index: the shaders are told the remap is the identity and skip it.
  EXPECT_TRUE(scene.light_remap_is_identity());
  const lighting::FrameCounts steady{.previous_lights = 2, .lights_keep_indices = true};
  EXPECT_EQ(lighting::make_frame_constants(both, 41, 31, 1, 1, steady, true).history.y, 1u);

  FrameSnapshot without = both;
  without.camera_cut = false;
  without.lights.erase(without.lights.begin() + 1);  // the light with stable id 1
  const runtime::ImageRGBA32F image = harness.render(without);
  ASSERT_EQ(scene.previous_light_count(), 2u);
  EXPECT_FALSE(scene.light_remap_is_identity());  // the shaders read the map this frame
  const lighting::FrameCounts removed{.previous_lights = 2, .lights_keep_indices = false};
  EXPECT_EQ(lighting::make_frame_constants(without, 41, 31, 2, 1, removed, true).history.y, 0u);
  EXPECT_EQ(scene.light_previous_to_current()[0], 0u);
  EXPECT_EQ(scene.light_previous_to_current()[1], gpu::kInvalidLight);
  EXPECT_EQ(scene.light_count(), 1u);
  EXPECT_EQ(harness.renderer().last_inputs().previous_light_count, 2u);
  // The remap reached the device too.
  const std::vector<std::uint32_t> remap =
      runtime::read_buffer<std::uint32_t>(device, scene.device_buffer(gpu::kSceneLightPreviousToCurrent));
  ASSERT_GE(remap.size(), 2u);
  EXPECT_EQ(remap[0], 0u);
  EXPECT_EQ(remap[1], gpu::kInvalidLight);

  // One light left: sampling it is exact, so the centre pixel is rho/pi * I / h^2 of the kept
  // light alone (the removed one would add 40 * cos^3 / d^2 more).
  const float* centre = image.at(20, 15);
  const float expected = 0.5f / gpu::kPi * 10.0f / 4.0f;
  EXPECT_NEAR(centre[0], expected, 2e-3f * expected);

  // Adding it back: a new index, unknown to the previous frame.
  const runtime::ImageRGBA32F again = harness.render(both);
  EXPECT_EQ(scene.light_record_count(), 2u);
  EXPECT_EQ(scene.light_previous_to_current().size(), 1u);
  EXPECT_EQ(scene.light_previous_to_current()[0], 0u);
  EXPECT_FALSE(scene.light_remap_is_identity());
  EXPECT_EQ(again.count_non_finite(), 0u);
  // A frame later both keep their indices again: the identity, not read.
  harness.render(both);
  EXPECT_TRUE(scene.light_remap_is_identity());
  ASSERT_EQ(scene.light_previous_to_current().size(), 2u);
  EXPECT_EQ(scene.light_previous_to_current()[1], 1u);
}

// The light spread measured at load reaches the integrators (ReSTIR's presampling tiles and
// local lists follow it); a level that starts without lights measured nothing, and its frames
// say so (the count rules decide).
TEST_F(FrameRendererTest, TheLightSpreadReachesTheIntegrators) {
  auto level = std::make_shared<const Level>(two_light_level());
  World world(level, {.threads = 1, .seed = 1, .fixed_dt = 1.0 / 60.0, .aspect = 41.0f / 31.0f});
  test::FrameHarness harness(device, shaders, level, 41, 31);
  harness.render(world.step());
  const lighting::LightSpread& spread = harness.renderer().scene().data().light_spread;
  ASSERT_GT(spread.points, 0u);
  EXPECT_GT(spread.spread, 0.0f);  // two bulbs of different power at different distances
  ASSERT_TRUE(harness.renderer().last_inputs().light_spread.has_value());
  EXPECT_EQ(*harness.renderer().last_inputs().light_spread, spread.spread);

  Level dark_level = two_light_level();
  dark_level.lights.clear();
  auto dark = std::make_shared<const Level>(std::move(dark_level));
  World dark_world(dark, {.threads = 1, .seed = 1, .fixed_dt = 1.0 / 60.0, .aspect = 41.0f / 31.0f});
  test::FrameHarness dark_harness(device, shaders, dark, 41, 31);
  dark_harness.render(dark_world.step());
  EXPECT_EQ(dark_harness.renderer().scene().data().light_spread.points, 0u);
  EXPECT_FALSE(dark_harness.renderer().last_inputs().light_spread.has_value());
}

TEST_F(FrameRendererTest, LightBuffersGrowWhenLightsAppear) {
  auto level = std::make_shared<const Level>(two_light_level());
  World world(level, {.threads = 1, .seed = 1, .fixed_dt = 1.0 / 60.0, .aspect = 41.0f / 31.0f});
  test::FrameHarness harness(device, shaders, level, 41, 31);
  const FrameSnapshot first = world.step();
  harness.render(first);
  const auto& scene = harness.renderer().scene();
  const VkDeviceSize initial_bytes = scene.device_buffer(gpu::kSceneLights).size();

  // 300 more dim point lights (new stable ids) over the plane: the light buffers must grow.
  FrameSnapshot more = first;
  more.camera_cut = false;
  for (std::uint32_t k = 0; k < 300; ++k) {
    SnapshotLight l = first.lights[0];
    l.stable_id = 100 + k;
    l.intensity = 0.01f;
    l.position = glm::vec3(-5.0f + 0.03f * static_cast<float>(k), 1.0f, 3.0f);
    more.lights.push_back(l);
  }
  for (int frame = 0; frame < 3; ++frame) {  // reuse after growth: old buffers retired safely
    const runtime::ImageRGBA32F image = harness.render(more);
    EXPECT_EQ(image.count_non_finite(), 0u);
  }
  EXPECT_EQ(scene.light_record_count(), 302u);
  EXPECT_GE(scene.device_buffer(gpu::kSceneLights).size(),
            302u * sizeof(gpu::GpuLight));
  EXPECT_GT(scene.device_buffer(gpu::kSceneLights).size(), initial_bytes);
  const std::vector<gpu::GpuLight> lights = runtime::read_buffer<gpu::GpuLight>(
      device, scene.device_buffer(gpu::kSceneLights));
  EXPECT_EQ(lights[301].p0.x, more.lights[301].position.x);
  // Back to two: the two survivors keep their ids, the 300 map to kInvalidLight.
  harness.render(first);
  ASSERT_EQ(scene.light_previous_to_current().size(), 302u);
  EXPECT_EQ(scene.light_previous_to_current()[0], 0u);
  EXPECT_EQ(scene.light_previous_to_current()[1], 1u);
  EXPECT_EQ(scene.light_previous_to_current()[2], gpu::kInvalidLight);
}

// Lights are drawn through two alias tables, the emissive triangles' and the analytic lights':
// a point light that flickers rewrites only the analytic lights' entries, and scene.upload copies
// only those, yet the device's table equals the CPU's in both groups afterwards.
TEST_F(FrameRendererTest, AFlickerRewritesOnlyTheAnalyticLightsTable) {
  Level with_panel = two_light_level();
  with_panel.meshes.push_back(make_plane(glm::vec2(1.0f, 1.0f)));  // two emissive triangles
  Material glow;
  glow.metallic = 0.0f;
  glow.emissive_factor = glm::vec3(1.0f, 0.8f, 0.6f);
  glow.emissive_strength = 5.0f;
  with_panel.materials.push_back(glow);
  Instance panel;
  panel.name = "panel";
  panel.mesh = 1;
  panel.material = 1;
  panel.transform.translation = glm::vec3(3.0f, 6.0f, 0.0f);
  panel.world = panel.transform.matrix();
  with_panel.instances.push_back(panel);
  auto level = std::make_shared<const Level>(std::move(with_panel));
  World world(level, {.threads = 1, .seed = 1, .fixed_dt = 1.0 / 60.0, .aspect = 41.0f / 31.0f});
  test::FrameHarness harness(device, shaders, level, 41, 31);
  const FrameSnapshot first = world.step();
  harness.render(first);
  const auto& scene = harness.renderer().scene();
  const lighting::LightTable& table = scene.data().lights;
  ASSERT_EQ(table.lights().size(), 4u);
  ASSERT_EQ(table.first_group_size(), 2u);

  FrameSnapshot brighter = first;
  brighter.camera_cut = false;
  brighter.lights[0].intensity *= 3.0f;
  const runtime::ImageRGBA32F image = harness.render(brighter);
  EXPECT_EQ(image.count_non_finite(), 0u);
  EXPECT_TRUE(scene.last_update().alias_rebuilt);
  EXPECT_EQ(table.alias_rewritten().first, 2u);
  EXPECT_EQ(table.alias_rewritten().count, 2u);
  const std::vector<gpu::AliasEntry> on_device =
      runtime::read_buffer<gpu::AliasEntry>(device, scene.device_buffer(gpu::kSceneLightAlias));
  ASSERT_GE(on_device.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(on_device[i].threshold, table.alias_entries()[i].threshold) << i;
    EXPECT_EQ(on_device[i].alias, table.alias_entries()[i].alias) << i;
    EXPECT_EQ(on_device[i].pdf, table.alias_entries()[i].pdf) << i;
  }
  double sum = 0.0;
  for (std::uint32_t i = 0; i < 4; ++i) sum += table.selection_pdf(i);
  EXPECT_NEAR(sum, 1.0, 1e-6);
}

}  // namespace
}  // namespace lantern
