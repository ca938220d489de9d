// Per-frame semantics of the world's snapshots: camera cuts, previous transforms, the camera on
// its path, and each behaviour's motion checked against its own closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/quaternion.hpp>

#include "engine/core/error.h"
#include "world_levels.h"

namespace lantern {
namespace {

constexpr float kPi = 3.14159265358979f;

const Instance& instance_named(const Level& level, const std::string& name, std::size_t* index) {
  for (std::size_t i = 0; i < level.instances.size(); ++i)
    if (level.instances[i].name == name) {
      *index = i;
      return level.instances[i];
    }
  throw std::runtime_error("no instance " + name);
}

std::size_t light_named(const Level& level, const std::string& name) {
  for (std::size_t i = 0; i < level.lights.size(); ++i)
    if (level.lights[i].name == name) return i;
  throw std::runtime_error("no light " + name);
}

TEST(WorldFrames, CameraCutOnFrameZeroAndWhenRequested) {
  World world(test::animated_level(), {.threads = 2});
  EXPECT_TRUE(world.step().camera_cut);
  EXPECT_FALSE(world.step().camera_cut);
  world.request_camera_cut();
  EXPECT_TRUE(world.step().camera_cut);
  EXPECT_FALSE(world.step().camera_cut);
}

TEST(WorldFrames, PreviousTransformsAreLastFramesTransforms) {
  const auto frames = test::run_frames(test::animated_level(), {.threads = 2}, 100);
  ASSERT_FALSE(frames[0].instances.empty());
  for (const SnapshotInstance& inst : frames[0].instances) {
    EXPECT_EQ(std::memcmp(&inst.prev_object_to_world, &inst.object_to_world, sizeof(glm::mat4)), 0);
  }
  EXPECT_EQ(std::memcmp(&frames[0].prev_camera, &frames[0].camera, sizeof(SnapshotCamera)), 0);
  for (std::size_t f = 1; f < frames.size(); ++f) {
    ASSERT_EQ(frames[f].instances.size(), frames[f - 1].instances.size());
    for (std::size_t i = 0; i < frames[f].instances.size(); ++i) {
      const SnapshotInstance& now = frames[f].instances[i];
      const SnapshotInstance& before = frames[f - 1].instances[i];
      ASSERT_EQ(now.stable_id, before.stable_id);
      EXPECT_EQ(std::memcmp(&now.prev_object_to_world, &before.object_to_world, sizeof(glm::mat4)),
                0)
          << "frame " << f << " instance " << i;
    }
    EXPECT_EQ(std::memcmp(&frames[f].prev_camera, &frames[f - 1].camera, sizeof(SnapshotCamera)),
              0);
  }
}

TEST(WorldFrames, CameraFollowsItsPath) {
  const auto level = test::animated_level();
  const CameraPath* path = level->find_path("fly");
  ASSERT_NE(path, nullptr);
  const auto frames =
      test::run_frames(level, {.threads = 1, .fixed_dt = 1.0 / 30.0, .aspect = 2.0f}, 80);
  for (const FrameSnapshot& s : frames) {
    const PathPose pose = path->evaluate(static_cast<float>(s.time));
    EXPECT_EQ(s.camera.position, pose.position) << "t=" << s.time;
    EXPECT_EQ(s.camera.orientation, pose.orientation) << "t=" << s.time;
    ASSERT_TRUE(pose.yfov.has_value());
    EXPECT_EQ(s.camera.yfov, *pose.yfov);
    EXPECT_EQ(s.camera.aspect, 2.0f);  // the level's camera gives none
    // The view matrix maps the camera position to the origin and its forward to -Z.
    const glm::vec4 eye = s.camera.view * glm::vec4(pose.position, 1.0f);
    EXPECT_NEAR(glm::length(glm::vec3(eye)), 0.0f, 1e-4f);
    const glm::vec3 fwd =
        glm::vec3(s.camera.view * glm::vec4(pose.orientation * glm::vec3(0, 0, -1), 0.0f));
    EXPECT_NEAR(fwd.z, -1.0f, 1e-5f);
  }
  // Past the last key (1.9 s) the non-looping path clamps.
  EXPECT_GT(frames.back().time, 2.0);
  EXPECT_EQ(frames.back().camera.position, path->keys.back().position);
}

TEST(WorldFrames, StaticCameraAndSwitchingPaths) {
  const auto level = test::cornell_level();
  ASSERT_TRUE(level->camera_path.empty());
  World world(level, {.threads = 2});
  for (int i = 0; i < 3; ++i) EXPECT_EQ(world.step().camera.position, level->camera.position);
  world.set_camera_path("dolly");
  const FrameSnapshot& s = world.step();
  EXPECT_EQ(s.camera.position,
            level->find_path("dolly")->evaluate(static_cast<float>(s.time)).position);
  EXPECT_NE(s.camera.position, level->camera.position);
  EXPECT_THROW(world.set_camera_path("no_such_path"), InputError);
}

TEST(WorldFrames, CornellOrbitingBoxStaysOnItsCircle) {
  const auto level = test::cornell_level();
  std::size_t index = 0;
  const Instance& box = instance_named(*level, "moving_box", &index);
  const auto& orbit = std::get<OrbitBehaviour>(*box.behaviour);
  const auto frames = test::run_frames(level, {.threads = 2}, 60);
  for (const FrameSnapshot& s : frames) {
    const glm::vec3 p(s.instances[index].object_to_world[3]);
    const float a = orbit.phase + orbit.speed * static_cast<float>(s.time);
    const glm::vec3 expected =
        orbit.center + orbit.radius * glm::vec3(std::cos(a), 0.0f, -std::sin(a));
    EXPECT_NEAR(glm::distance(p, expected), 0.0f, 1e-5f) << "t=" << s.time;
  }
  // Static instances keep the level's exact matrix.
  std::size_t floor = 0;
  instance_named(*level, "floor", &floor);
  EXPECT_EQ(frames.back().instances[floor].object_to_world, level->instances[floor].world);
}

TEST(WorldFrames, RotateFollowPathOrbitAndFlickerMatchTheirDefinitions) {
  const auto level = test::animated_level();
  std::size_t spinner = 0, rider = 0;
  const Instance& spin = instance_named(*level, "spinner", &spinner);
  instance_named(*level, "rider", &rider);
  const std::size_t firefly = light_named(*level, "firefly");
  const std::size_t candle = light_named(*level, "candle");
  const std::size_t candle2 = light_named(*level, "flicker_two");
  const std::size_t beam = light_named(*level, "beam");
  const CameraPath& lap = *level->find_path("lap");
  const double dt = 1.0 / 60.0;
  const auto frames = test::run_frames(level, {.threads = 4, .fixed_dt = dt}, 100);

  const glm::vec3 axis = glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
  int candles_differ = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const FrameSnapshot& s = frames[f];
    const auto t = static_cast<float>(s.time);
    SCOPED_TRACE("frame " + std::to_string(f));
    // rotate: the object-space axis is fixed; the rotation angle from the start is speed·t.
    const glm::mat4& m = s.instances[spinner].object_to_world;
    const glm::vec3 world_axis =
        glm::normalize(glm::vec3(m * glm::vec4(axis / glm::vec3(1, 2, 1), 0.0f)));
    const glm::vec3 rest_axis = glm::normalize(spin.transform.rotation * axis);
    EXPECT_GT(glm::dot(world_axis, rest_axis), 0.9999f);
    const glm::quat delta =
        glm::inverse(spin.transform.rotation) *
        glm::quat_cast(glm::mat3(glm::normalize(glm::vec3(m[0])), glm::normalize(glm::vec3(m[1])),
                                 glm::normalize(glm::vec3(m[2]))));
    const float expected_angle = std::fmod(glm::radians(140.0f) * t, 2.0f * kPi);
    const float angle = glm::angle(delta);
    EXPECT_NEAR(
        std::min(std::abs(angle - expected_angle), 2.0f * kPi - std::abs(angle - expected_angle)),
        0.0f, 1e-3f);
    // follow_path (loop, speed 2): the position on the 0.9 s lap at 2t wrapped.
    const float lap_t = std::fmod(2.0f * t, lap.duration());
    EXPECT_NEAR(glm::distance(glm::vec3(s.instances[rider].object_to_world[3]),
                              lap.evaluate(lap_t).position),
                0.0f, 1e-4f);
    // orbit on a light: centre (0, 1.5, 0), radius 0.8, 75°/s from 30°.
    const float a = glm::radians(30.0f) + glm::radians(75.0f) * t;
    const glm::vec3 orbit_expected =
        glm::vec3(0, 1.5f, 0) + 0.8f * glm::vec3(std::cos(a), 0.0f, -std::sin(a));
    EXPECT_NEAR(glm::distance(s.lights[firefly].position, orbit_expected), 0.0f, 1e-5f);
    // flicker: within [min, max] × intensity, smooth (smoothstep slope ≤ 1.5 per cell).
    for (std::size_t l : {candle, candle2}) {
      const float base = level->lights[l].intensity;
      EXPECT_GE(s.lights[l].intensity, 0.3f * base);
      EXPECT_LE(s.lights[l].intensity, 1.2f * base);
      if (f > 0) {
        const float max_step = (1.2f - 0.3f) * base * 1.5f * 9.0f * static_cast<float>(dt) * 1.01f;
        EXPECT_LE(std::abs(s.lights[l].intensity - frames[f - 1].lights[l].intensity), max_step);
      }
    }
    candles_differ += s.lights[candle].intensity / 3.0f != s.lights[candle2].intensity / 2.0f;
    // rotate on a spot light: it tilts about its local X, so its beam sweeps at 45°/s.
    const glm::vec3 beam_rest = level->lights[beam].direction();
    EXPECT_NEAR(std::acos(std::clamp(glm::dot(s.lights[beam].direction, beam_rest), -1.0f, 1.0f)),
                std::acos(std::cos(glm::radians(45.0f) * t)), 1e-3f);
    // Lights without flicker keep their intensity.
    EXPECT_EQ(s.lights[firefly].intensity, level->lights[firefly].intensity);
  }
  // Same behaviour and seed, different stable ids: different flicker.
  EXPECT_GT(candles_differ, 90);
  // The looping lap wrapped at least once within the run (2 × 100/60 s > 0.9 s).
  EXPECT_GT(2.0 * frames.back().time, static_cast<double>(lap.duration()));
}

TEST(WorldFrames, SnapshotCarriesFrameDataAndLevel) {
  const auto level = test::animated_level();
  World world(level, {.threads = 1, .seed = 99, .fixed_dt = 0.025});
  for (std::uint64_t i = 0; i < 5; ++i) {
    const FrameSnapshot& s = world.step();
    EXPECT_EQ(s.frame_index, i);
    EXPECT_DOUBLE_EQ(s.time, 0.025 * static_cast<double>(i + 1));
    EXPECT_EQ(s.dt, 0.025);
    EXPECT_EQ(s.seed, 99u);
    EXPECT_EQ(s.level.get(), level.get());
    EXPECT_EQ(s.instances.size(), level->instances.size());
    ASSERT_EQ(s.lights.size(), level->lights.size());
    for (std::size_t l = 0; l < s.lights.size(); ++l) EXPECT_EQ(s.lights[l].stable_id, l);
  }
  // A held snapshot survives later steps unchanged.
  const std::shared_ptr<const FrameSnapshot> held = world.latest();
  const std::uint64_t index = held->frame_index;
  world.step();
  EXPECT_EQ(held->frame_index, index);
  EXPECT_NE(world.latest().get(), held.get());
}

TEST(WorldFrames, BadOptionsAreInputErrors) {
  const auto level = test::animated_level();
  EXPECT_THROW(World(level, {.threads = 0}), InputError);
  EXPECT_THROW(World(level, {.fixed_dt = 0.0}), InputError);
  EXPECT_THROW(World(level, {.aspect = -1.0f}), InputError);
}

}  // namespace
}  // namespace lantern
