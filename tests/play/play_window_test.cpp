// `lantern play` in a real window (Xvfb in CI): scripted input flies the camera, opens the panel,
// toggles lights and integrators; a broken shader edit keeps the old pipelines rendering and a
// fixed one reloads. run_play throws on any validation error (LANTERN_VALIDATION=1).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/lantern/play/play_session.h"
#include "tests/runtime/scratch_dir.h"

namespace lantern::app {
namespace {

namespace fs = std::filesystem;

bool have_display() {
  const char* d = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (d != nullptr && *d != '\0') || (w != nullptr && *w != '\0');
}

PlayConfig small_config(const std::string& script) {
  PlayConfig c;
  c.level = "cornell_lights";
  c.width = 96;
  c.height = 54;
  c.script = InputScript::parse(script, "test script");
  return c;
}

TEST(PlayWindow, ScriptedFlightPanelAndLights) {
  if (!have_display()) FAIL() << "needs a display: run under xvfb-run (scripts/test.sh does)";
  const PlayReport r =
      run_play(small_config("frame 1 key F1 press\n"
                            "frame 2 mouse right down\nframe 2 key W down\nframe 3 move 20 -8\n"
                            "frame 5 key W up\nframe 5 mouse right up\n"
                            "frame 6 key F press\nframe 7 key SPACE press\nframe 8 key L press\n"
                            "frame 9 key F1 press\nframe 11 quit\n"));
  EXPECT_EQ(r.frames, 11u);
  EXPECT_GT(r.camera_travel, 0.01);  // W held for 3 frames
  EXPECT_GE(r.manual_frames, 3u);
  EXPECT_EQ(r.camera_cuts, 1u);   // frame 0 only: flying is not a cut
  EXPECT_EQ(r.panel_frames, 8u);  // F1 on frame 1, off on frame 9
  EXPECT_GT(r.max_ui_triangles, 100u);
  EXPECT_TRUE(r.flashlight);
  EXPECT_EQ(r.spawned_lights, 1u);
  EXPECT_EQ(r.integrator, "restir");
  EXPECT_EQ(r.validation_errors, 0u);
  EXPECT_FALSE(r.frame_ms.empty());
}

// Number keys switch integrators (2 baseline, 3 progressive reference, 1 back to ReSTIR); V
// steps the debug view: on the reference it waits in the panel (w), the switch to ReSTIR takes
// it, and V on the running ReSTIR reaches it live (m).
TEST(PlayWindow, IntegratorSwitchAndProgressiveReference) {
  if (!have_display()) FAIL() << "needs a display: run under xvfb-run (scripts/test.sh does)";
  PlayConfig c = small_config(
      "frame 1 key 2 press\nframe 3 key 3 press\nframe 3 key F1 press\n"
      "frame 4 key V press\nframe 6 key 1 press\nframe 7 key V press\nframe 9 quit\n");
  c.width = 64;
  c.height = 36;
  const PlayReport r = run_play(c);
  EXPECT_EQ(r.frames, 9u);
  EXPECT_EQ(r.rebuilds, 3u);
  EXPECT_EQ(r.integrator, "restir");
  std::string view;
  for (const auto& [key, value] : r.integrator_settings)
    if (key == "debug_view") view = value;
  EXPECT_EQ(view, "m");
  EXPECT_EQ(r.camera_travel, 0.0);
  EXPECT_EQ(r.validation_errors, 0u);
}

// Dynamic resolution under scripted input: an unreachable target (0.5 ms) drives the internal
// size down to its floor and no further; a generous one (10 s) keeps the window size. The output
// stays the window's either way, and the panel (open) shows it all.
TEST(PlayWindow, DynamicResolutionStaysWithinItsLimits) {
  if (!have_display()) FAIL() << "needs a display: run under xvfb-run (scripts/test.sh does)";
  PlayConfig c = small_config("frame 1 key F1 press\nframe 2 key W down\nframe 24 quit\n");
  c.width = 128;
  c.height = 72;
  c.dynamic_resolution = {.target_ms = 0.5, .min_scale = 0.25f};
  const PlayReport fast = run_play(c);
  EXPECT_EQ(fast.frames, 24u);
  EXPECT_EQ(fast.output_width, 128u);
  EXPECT_EQ(fast.output_height, 72u);
  EXPECT_EQ(fast.min_internal_width, 32u);  // the floor: 25% of the window
  EXPECT_EQ(fast.min_internal_height, 18u);
  EXPECT_LE(fast.max_internal_width, 128u);
  EXPECT_LE(fast.max_internal_height, 72u);
  EXPECT_GE(fast.resolution_changes, 1u);
  EXPECT_EQ(fast.validation_errors, 0u);

  c.dynamic_resolution.target_ms = 10000.0;
  const PlayReport slow = run_play(c);
  EXPECT_EQ(slow.min_internal_width, 128u);
  EXPECT_EQ(slow.min_internal_height, 72u);
  EXPECT_EQ(slow.resolution_changes, 0u);
}

TEST(PlayWindow, BrokenShaderKeepsRenderingAndFixedShaderReloads) {
  if (!have_display()) FAIL() << "needs a display: run under xvfb-run (scripts/test.sh does)";
  const fs::path dir = lantern::test::process_scratch_dir() / "shaders";
  fs::remove_all(dir);
  fs::copy(LANTERN_TEST_SHADER_SOURCE_DIR, dir, fs::copy_options::recursive);
  const fs::path shader = dir / "frame" / "frame_output.comp";
  std::string original;
  {
    std::ifstream in(shader);
    std::stringstream text;
    text << in.rdbuf();
    original = text.str();
  }
  PlayConfig c = small_config("frame 9 quit\n");
  c.width = 64;
  c.height = 36;
  c.shader_source_dir = dir;
  c.watch_interval_s = 0.0;
  c.on_frame = [&](std::uint64_t frame) {
    if (frame == 2) std::ofstream(shader) << original << "\nthis is not GLSL;\n";
    if (frame == 5) std::ofstream(shader) << original << "\n// fixed\n";
  };
  const PlayReport r = run_play(c);
  fs::remove_all(dir);
  EXPECT_EQ(r.frames, 9u);  // rendering went on with the old pipelines
  EXPECT_GE(r.reload_failures, 1u);
  EXPECT_NE(r.last_reload_error.find("frame/frame_output.comp"), std::string::npos)
      << r.last_reload_error;
  EXPECT_GE(r.reloads_ok, 1u);
  EXPECT_EQ(r.validation_errors, 0u);
}

}  // namespace
}  // namespace lantern::app
