// glTF node animation (tests/level/data/animated_mesh.gltf, hand-written): a mesh node under a
// moved and turned parent, animated in translation (3 keys) and scale, becomes a world-space path
// that its instance follows, in the level data and in a running World.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <memory>
#include <variant>

#include "engine/level/level_loader.h"
#include "engine/world/world.h"
#include "tests/level/test_files.h"

namespace lantern {
namespace {

void expect_near(glm::vec3 a, glm::vec3 b, float eps = 1e-4f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

// The file's parent node "carrier": translation (10, 0, 0), 90° about +Y.
glm::mat4 carrier_world() {
  return glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0)) *
         glm::mat4_cast(glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 1, 0)));
}

// The translation keys of node "mover" at times 0, 1, 2 s, in the parent's space.
const glm::vec3 kLocalKeys[3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};

const FollowPathBehaviour& follow_of(const Instance& inst) {
  EXPECT_TRUE(inst.behaviour.has_value());
  EXPECT_TRUE(std::holds_alternative<FollowPathBehaviour>(*inst.behaviour));
  return std::get<FollowPathBehaviour>(*inst.behaviour);
}

TEST(GltfNodeAnimation, MeshNodeFollowsALoopingPathThroughItsKeysInWorldSpace) {
  const Level level = load_level(test::data_dir() / "animated_mesh.gltf");
  ASSERT_EQ(level.instances.size(), 1u);
  ASSERT_EQ(level.paths.size(), 1u);
  EXPECT_TRUE(level.camera_path.empty());  // no camera node: nothing for the camera to follow
  const CameraPath& path = level.paths[0];
  EXPECT_EQ(path.name, "animated_mesh/mover");
  ASSERT_TRUE(path.problem().empty()) << path.problem();

  ASSERT_TRUE(level.instances[0].behaviour.has_value());
  const FollowPathBehaviour& follow = follow_of(level.instances[0]);
  EXPECT_EQ(follow.path, path.name);
  EXPECT_FLOAT_EQ(follow.speed, 1.0f);
  EXPECT_TRUE(follow.loop);

  ASSERT_EQ(path.keys.size(), 3u);
  const glm::quat parent_rotation = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 1, 0));
  for (std::size_t k = 0; k < 3; ++k) {
    const glm::vec3 world = glm::vec3(carrier_world() * glm::vec4(kLocalKeys[k], 1.0f));
    EXPECT_FLOAT_EQ(path.keys[k].time, static_cast<float>(k));
    expect_near(path.keys[k].position, world);
    const PathPose pose = path.evaluate(path.keys[k].time);  // the smooth path passes the keys
    expect_near(pose.position, world);
    EXPECT_NEAR(std::abs(glm::dot(pose.orientation, parent_rotation)), 1.0f, 1e-5f);
  }
  // The second key, worked by hand: +X in the parent turned 90° about +Y is -Z.
  expect_near(path.keys[1].position, glm::vec3(10, 0, -1));
  // The scale channel is ignored: the instance keeps the node's rest scale.
  expect_near(level.instances[0].transform.scale, glm::vec3(2));
}

TEST(GltfNodeAnimation, RunningWorldMovesTheInstanceAlongThePathKeepingItsScale) {
  auto level = std::make_shared<const Level>(load_level(test::data_dir() / "animated_mesh.gltf"));
  const CameraPath& path = level->paths.at(0);
  World world(level, {.threads = 1, .seed = 1, .fixed_dt = 0.25});
  glm::vec3 first_position{0.0f};
  float largest_move = 0.0f;
  for (int step = 0; step < 10; ++step) {  // 2.5 s: past the end, so the loop wraps once
    const FrameSnapshot& frame = world.step();
    ASSERT_EQ(frame.instances.size(), 1u);
    const glm::mat4& m = frame.instances[0].object_to_world;
    const glm::vec3 position(m[3]);
    const float t = static_cast<float>(frame.time);
    expect_near(position,
                path.evaluate(path.start_time() + std::fmod(t, path.duration())).position);
    for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(glm::length(glm::vec3(m[axis])), 2.0f, 1e-4f);
    if (step == 0) first_position = position;
    largest_move = std::max(largest_move, glm::length(position - first_position));
  }
  EXPECT_GT(largest_move, 0.9f);  // keys span about 1.4 m: the instance really travels
}

TEST(GltfNodeAnimation, EachPlacementOfAnAssetGetsItsOwnPathInWorldSpace) {
  const std::filesystem::path file = test::scratch("two_movers.json");
  const std::string asset = (test::data_dir() / "animated_mesh.gltf").string();
  test::write_text(file, R"({ "assets": [ { "file": ")" + asset + R"(" },
                                        { "file": ")" +
                             asset + R"(", "translation": [0, 5, 0] } ] })");
  const Level level = load_level(file);
  ASSERT_EQ(level.instances.size(), 2u);
  ASSERT_EQ(level.paths.size(), 2u);
  EXPECT_EQ(level.paths[0].name, "animated_mesh/mover");
  EXPECT_EQ(level.paths[1].name, "animated_mesh/mover#2");
  EXPECT_EQ(follow_of(level.instances[0]).path, level.paths[0].name);
  EXPECT_EQ(follow_of(level.instances[1]).path, level.paths[1].name);
  for (std::size_t k = 0; k < 3; ++k)
    expect_near(level.paths[1].keys[k].position,
                level.paths[0].keys[k].position + glm::vec3(0, 5, 0));
}

}  // namespace
}  // namespace lantern
