// Same level + seed → bitwise-identical snapshots every frame, for 1, 2 and 4 scheduler threads;
// a different seed changes flicker (so the comparison can fail).
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "world_levels.h"

namespace lantern {
namespace {

constexpr int kFrames = 100;

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expect_identical_runs(const std::shared_ptr<const Level>& level, const std::string& what) {
  const std::vector<FrameSnapshot> reference =
      test::run_frames(level, {.threads = 1, .seed = 42}, kFrames);
  for (unsigned threads : {2u, 4u}) {
    const std::vector<FrameSnapshot> run =
        test::run_frames(level, {.threads = threads, .seed = 42}, kFrames);
    ASSERT_EQ(run.size(), reference.size());
    for (int f = 0; f < kFrames; ++f) {
      const FrameSnapshot& a = reference[static_cast<std::size_t>(f)];
      const FrameSnapshot& b = run[static_cast<std::size_t>(f)];
      SCOPED_TRACE(what + ", " + std::to_string(threads) + " threads, frame " + std::to_string(f));
      ASSERT_EQ(a.frame_index, b.frame_index);
      ASSERT_EQ(std::memcmp(&a.time, &b.time, sizeof a.time), 0);
      ASSERT_EQ(a.camera_cut, b.camera_cut);
      ASSERT_EQ(std::memcmp(&a.camera, &b.camera, sizeof(SnapshotCamera)), 0);
      ASSERT_EQ(std::memcmp(&a.prev_camera, &b.prev_camera, sizeof(SnapshotCamera)), 0);
      ASSERT_TRUE(same_bytes(a.instances, b.instances));
      ASSERT_TRUE(same_bytes(a.lights, b.lights));
    }
  }
}

TEST(WorldDeterminism, AnimatedLevelIsBitwiseIdenticalAcrossThreadCounts) {
  expect_identical_runs(test::animated_level(), "animated level");
}

TEST(WorldDeterminism, CornellLevelIsBitwiseIdenticalAcrossThreadCounts) {
  expect_identical_runs(test::cornell_level(), "cornell_lights");
}

TEST(WorldDeterminism, AnimatedLevelActuallyMoves) {
  // Guards the tests above against comparing frozen worlds.
  const auto frames = test::run_frames(test::animated_level(), {.threads = 1, .seed = 42}, kFrames);
  int moved = 0, flickered = 0;
  for (std::size_t f = 1; f < frames.size(); ++f) {
    moved += !same_bytes(frames[f].instances, frames[f - 1].instances);
    flickered += frames[f].lights[0].intensity != frames[f - 1].lights[0].intensity;
  }
  EXPECT_EQ(moved, kFrames - 1);
  EXPECT_EQ(flickered, kFrames - 1);
}

TEST(WorldDeterminism, SeedChangesFlickerOnly) {
  const auto level = test::animated_level();
  const auto a = test::run_frames(level, {.threads = 2, .seed = 1}, 30);
  const auto b = test::run_frames(level, {.threads = 2, .seed = 2}, 30);
  int differing = 0;
  for (std::size_t f = 0; f < a.size(); ++f) {
    EXPECT_EQ(std::memcmp(&a[f].camera, &b[f].camera, sizeof(SnapshotCamera)), 0);
    ASSERT_EQ(a[f].lights.size(), b[f].lights.size());
    for (std::size_t i = 0; i < a[f].lights.size(); ++i) {
      EXPECT_EQ(a[f].lights[i].position, b[f].lights[i].position);
      differing += a[f].lights[i].intensity != b[f].lights[i].intensity;
    }
  }
  EXPECT_GT(differing, 30);  // two flickering lights × 30 frames, nearly all differ
}

}  // namespace
}  // namespace lantern
