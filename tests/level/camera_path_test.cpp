// Camera paths: interpolation passes through keyframes, is C1 in time (numerically), rotations
// pass through their keys and stay continuous, clamping and looping, invalid paths are named.
#include "engine/scene/camera_path.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/scene/camera.h"

namespace lantern {
namespace {

CameraPath uneven_path(bool loop) {
  CameraPath p;
  p.name = "uneven";
  p.loop = loop;
  // Uneven spacing in both time and distance, with a sharp turn at key 2.
  const std::vector<std::pair<float, glm::vec3>> keys = {{0.0f, {0, 1, 0}},
                                                         {1.0f, {4, 1, 0}},
                                                         {1.5f, {4.5f, 1.5f, 0.5f}},
                                                         {4.0f, {0, 3, 6}},
                                                         {5.0f, {-2, 1, 2}}};
  for (const auto& [t, pos] : keys)
    p.keys.push_back({t, pos, look_at_orientation(pos, glm::vec3(0, 0.5f, 1)),
                      std::optional<float>(0.5f + 0.1f * t)});
  if (loop) {
    PathKey closing = p.keys.front();
    closing.time = 7.0f;
    p.keys.push_back(closing);
  }
  return p;
}

// One-sided second-order derivative estimates at t from the left and from the right.
glm::vec3 left_velocity(const CameraPath& p, float t, float h) {
  return (3.0f * p.evaluate(t).position - 4.0f * p.evaluate(t - h).position +
          p.evaluate(t - 2 * h).position) /
         (2 * h);
}
glm::vec3 right_velocity(const CameraPath& p, float t, float h) {
  return (-3.0f * p.evaluate(t).position + 4.0f * p.evaluate(t + h).position -
          p.evaluate(t + 2 * h).position) /
         (2 * h);
}

float angle_between(const glm::quat& a, const glm::quat& b) {
  return 2.0f * std::acos(std::min(1.0f, std::abs(glm::dot(glm::normalize(a), glm::normalize(b)))));
}

TEST(CameraPath, PassesThroughEveryKeyframe) {
  const CameraPath p = uneven_path(false);
  ASSERT_EQ(p.problem(), "");
  for (const PathKey& k : p.keys) {
    const PathPose pose = p.evaluate(k.time);
    EXPECT_LT(glm::length(pose.position - k.position), 1e-4f) << "t=" << k.time;
    EXPECT_LT(angle_between(pose.orientation, k.orientation), 1e-3f) << "t=" << k.time;
    ASSERT_TRUE(pose.yfov);
    EXPECT_NEAR(*pose.yfov, *k.yfov, 1e-5f);
  }
}

TEST(CameraPath, PositionIsC1AtInteriorKeys) {
  for (bool loop : {false, true}) {
    const CameraPath p = uneven_path(loop);
    for (std::size_t i = 1; i + 1 < p.keys.size(); ++i) {
      const float t = p.keys[i].time;
      const glm::vec3 l = left_velocity(p, t, 1e-2f), r = right_velocity(p, t, 1e-2f);
      const float speed = std::max(glm::length(l), glm::length(r));
      ASSERT_GT(speed, 0.1f) << "key " << i;
      EXPECT_LT(glm::length(l - r) / speed, 0.02f)
          << "velocity jumps at key " << i << " (loop " << loop << ")";
    }
  }
}

TEST(CameraPath, ALoopIsC1AcrossTheWrap) {
  const CameraPath p = uneven_path(true);
  const float end = p.end_time();
  const glm::vec3 before = left_velocity(p, end, 1e-2f);
  const glm::vec3 after = right_velocity(p, p.start_time(), 1e-2f);
  EXPECT_LT(glm::length(before - after) / glm::length(after), 0.02f);
  EXPECT_LT(glm::length(p.evaluate(end + 1.25f).position - p.evaluate(1.25f).position), 1e-4f);
  EXPECT_LT(glm::length(p.evaluate(-0.5f).position - p.evaluate(end - 0.5f).position), 1e-4f);
}

TEST(CameraPath, RotationIsContinuous) {
  const CameraPath p = uneven_path(false);
  float worst = 0.0f;
  for (float t = 0.0f; t < p.end_time(); t += 1e-3f)
    worst = std::max(worst,
                     angle_between(p.evaluate(t).orientation, p.evaluate(t + 1e-3f).orientation));
  EXPECT_LT(worst, 0.02f);  // radians per millisecond step: no flips or jumps
}

TEST(CameraPath, ClampsOutsideItsTimeRange) {
  const CameraPath p = uneven_path(false);
  EXPECT_LT(glm::length(p.evaluate(-3.0f).position - p.keys.front().position), 1e-6f);
  EXPECT_LT(glm::length(p.evaluate(99.0f).position - p.keys.back().position), 1e-6f);
}

TEST(CameraPath, ProblemsAreDescribed) {
  CameraPath one;
  one.name = "solo";
  one.keys.push_back({});
  EXPECT_NE(one.problem().find("1 keyframe"), std::string::npos);
  CameraPath backwards = uneven_path(false);
  backwards.keys[2].time = 0.5f;
  EXPECT_NE(backwards.problem().find("keyframe 2"), std::string::npos);
  CameraPath mixed = uneven_path(false);
  mixed.keys[3].yfov.reset();
  EXPECT_NE(mixed.problem().find("fov"), std::string::npos);
}

}  // namespace
}  // namespace lantern
