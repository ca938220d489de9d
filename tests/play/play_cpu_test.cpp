// Scripted input parsing and the engine-side fly camera (no window, no GPU).
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "apps/lantern/play/dynamic_resolution.h"
#include "apps/lantern/play/play_input.h"
#include "engine/core/error.h"
#include "engine/level/level_loader.h"
#include "engine/world/fly_camera.h"
#include "engine/world/world.h"

namespace lantern::app {
namespace {

TEST(PlayScript, EventsApplyOnTheirFrameAndKeysStayHeld) {
  InputScript script = InputScript::parse(
      "# comment\nframe 1 key W down\nframe 3 key w up\nframe 2 key F1 press\n"
      "frame 2 mouse right down\nframe 2 move 10 -4\nframe 4 scroll 2\nframe 5 quit\n",
      "test");
  std::vector<PlayInput> frames;
  for (std::uint64_t f = 0; f < 6; ++f) {
    PlayInput in;
    script.apply(f, in);
    frames.push_back(in);
  }
  EXPECT_FALSE(frames[0].key(GLFW_KEY_W));
  EXPECT_TRUE(frames[1].key(GLFW_KEY_W));
  EXPECT_TRUE(frames[2].key(GLFW_KEY_W));
  EXPECT_FALSE(frames[3].key(GLFW_KEY_W));
  EXPECT_TRUE(pressed(frames[2], frames[1], GLFW_KEY_F1));
  EXPECT_FALSE(frames[3].key(GLFW_KEY_F1));  // press = down for one frame
  EXPECT_TRUE(frames[2].button(GLFW_MOUSE_BUTTON_RIGHT));
  EXPECT_TRUE(frames[4].button(GLFW_MOUSE_BUTTON_RIGHT));
  EXPECT_DOUBLE_EQ(frames[2].cursor_dx, 10.0);
  EXPECT_DOUBLE_EQ(frames[2].cursor_dy, -4.0);
  EXPECT_DOUBLE_EQ(frames[3].cursor_dx, 0.0);
  EXPECT_DOUBLE_EQ(frames[4].scroll_y, 2.0);
  EXPECT_FALSE(frames[4].quit);
  EXPECT_TRUE(frames[5].quit);
}

TEST(PlayScript, BadLinesNameFileAndLine) {
  const auto message = [](const std::string& text) {
    try {
      InputScript::parse(text, "s.txt");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("frame 1 key W down\nframe x key W down\n").find("s.txt:2"), std::string::npos);
  EXPECT_NE(message("frame 1 key BOGUS down\n").find("BOGUS"), std::string::npos);
  EXPECT_NE(message("frame 1 key W sideways\n").find("sideways"), std::string::npos);
  EXPECT_NE(message("frame 1 dance\n").find("dance"), std::string::npos);
  EXPECT_NE(message("frame 1 move 1\n").find("s.txt:1"), std::string::npos);
}

TEST(FlyCamera, YawPitchRoundTrip) {
  for (float yaw : {-2.5f, -0.3f, 0.0f, 1.0f, 3.0f}) {
    for (float pitch : {-1.2f, 0.0f, 0.7f}) {
      const glm::vec2 yp = yaw_pitch_of(orientation_of(yaw, pitch));
      EXPECT_NEAR(yp.x, yaw, 1e-4f);
      EXPECT_NEAR(yp.y, pitch, 1e-4f);
    }
  }
  // yaw 0, pitch 0 looks down -Z; positive yaw turns left (towards -X).
  const glm::vec3 f = orientation_of(0.5f, 0.0f) * glm::vec3(0.0f, 0.0f, -1.0f);
  EXPECT_LT(f.x, 0.0f);
}

TEST(FlyCamera, ManualControlMovesTheCameraWithHistoryAndNoCut) {
  auto level = std::make_shared<const Level>(load_level_argument("cornell_lights"));
  World world(level, {.threads = 1, .seed = 1, .fixed_dt = 1.0 / 60.0});
  enable_fly_camera(world);
  const FrameSnapshot& first = world.step();
  EXPECT_TRUE(first.camera_cut);
  const glm::vec3 start = world.latest()->camera.position;
  const glm::vec3 forward = world.latest()->camera.orientation * glm::vec3(0.0f, 0.0f, -1.0f);

  take_manual_control(world);
  FlyCamera& fly = fly_camera(world);
  fly.speed = 3.0f;
  fly.input = FlyCameraInput{.move = {0.0f, 0.0f, 1.0f}, .dt = 0.5f};
  const FrameSnapshot& moved = world.step();
  EXPECT_FALSE(moved.camera_cut);
  const glm::vec3 travelled = moved.camera.position - start;
  EXPECT_NEAR(glm::length(travelled), 1.5f, 1e-3f);
  EXPECT_GT(glm::dot(glm::normalize(travelled), forward), 0.99f);
  // The previous camera is last frame's: motion vectors see the move.
  EXPECT_NEAR(glm::length(moved.prev_camera.position - start), 0.0f, 1e-5f);
  const glm::quat moved_orientation = moved.camera.orientation;  // `moved` is reused by step()

  // Turning: yaw input rotates the view; the path no longer drives the camera.
  fly.input = FlyCameraInput{.yaw = 0.3f};
  const glm::vec3 before = world.latest()->camera.position;
  const FrameSnapshot& turned = world.step();
  EXPECT_FALSE(turned.camera_cut);
  EXPECT_NEAR(glm::length(turned.camera.position - before), 0.0f, 1e-5f);
  EXPECT_NEAR(yaw_pitch_of(turned.camera.orientation).x - yaw_pitch_of(moved_orientation).x, 0.3f,
              1e-3f);

  resume_camera_path(world);
  EXPECT_FALSE(fly.active);
  // Back on the path is a teleport (a cut); a level without a path keeps the camera still.
  EXPECT_EQ(world.step().camera_cut, !level->camera_path.empty());
}

// Dynamic resolution: too slow -> the scale drops (by sqrt of the time ratio, after the settle
// frames), never below the floor; on target it holds; too fast -> back up, never above 1.
TEST(DynamicResolution, HoldsTheTargetWithinItsLimits) {
  DynamicResolution d({.target_ms = 30.0, .min_scale = 0.25f});
  for (int f = 0; f < DynamicResolution::kSettleFrames - 1; ++f) EXPECT_EQ(d.update(120.0), 1.0f);
  EXPECT_NEAR(d.update(120.0), 0.5f, 1e-3f);  // 4x the time: half the size per axis
  for (int f = 0; f < 40; ++f) d.update(1000.0);
  EXPECT_FLOAT_EQ(d.scale(), 0.25f);
  EXPECT_EQ(d.internal_size(320, 180), (std::pair<std::uint32_t, std::uint32_t>{80, 45}));
  EXPECT_EQ(d.internal_size(40, 20), (std::pair<std::uint32_t, std::uint32_t>{16, 16}));
  const float held = d.scale();
  for (int f = 0; f < 20; ++f) d.update(31.0);  // within the dead band
  EXPECT_EQ(d.scale(), held);
  for (int f = 0; f < 40; ++f) d.update(1.0);
  EXPECT_FLOAT_EQ(d.scale(), 1.0f);
  EXPECT_EQ(d.internal_size(320, 180), (std::pair<std::uint32_t, std::uint32_t>{320, 180}));
}

TEST(DynamicResolution, OffAtTargetZeroAndIgnoresBadTimes) {
  DynamicResolution off({.target_ms = 0.0, .min_scale = 0.25f});
  for (int f = 0; f < 20; ++f) off.update(500.0);
  EXPECT_EQ(off.scale(), 1.0f);
  DynamicResolution d({.target_ms = 30.0, .min_scale = 0.25f});
  for (int f = 0; f < 20; ++f) {
    d.update(std::nan(""));
    d.update(-5.0);
  }
  EXPECT_EQ(d.scale(), 1.0f);
}

}  // namespace
}  // namespace lantern::app
