// ReSTIR DI end to end on lavapipe (small sizes, few frames), through FrameRenderer as the
// renderer runs it (bias: restir_bias_test.cpp): temporal reuse lowering error on a moving
// camera, disocclusion recovery, light removal, camera cut, NaN/Inf guards. Tolerances are stated at each assertion; figures are printed for the report.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "engine/core/error.h"
#include "lighting/frame/tile_order.h"
#include "lighting/restir/restir_pass.h"
#include "lighting/visibility/visibility_backend.h"
#include "shared/pixel_groups.h"
#include "shared/restir.h"
#include "shared/scene.h"
#include "tests/restir/restir_test_support.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {

using runtime::ImageRGBA32F;
using test::RenderHarness;

constexpr std::uint32_t kW = 96;
constexpr std::uint32_t kH = 54;

class RestirGpuTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;

  std::shared_ptr<const Level> cornell() {
    static std::shared_ptr<const Level> level =
        std::make_shared<const Level>(load_level_argument("cornell_lights"));
    return level;
  }

  // Mean of `frames` baseline frames of a frozen snapshot: the unbiased reference.
  ImageRGBA32F baseline_mean(std::shared_ptr<const Level> level, const FrameSnapshot& snapshot,
                             std::uint32_t frames) {
    RenderHarness h(device, shaders, level, test::make_baseline(device, shaders), kW, kH);
    runtime::ImageAccumulator acc;
    FrameSnapshot s = snapshot;
    for (std::uint32_t f = 0; f < frames; ++f) {
      acc.add(h.render(s));
      s = frozen(s);
    }
    return acc.mean();
  }
};

// Bias on lit surfaces (balance, pairwise, none and the single-stage configurations, over
// independent seeds against the reference integrator): restir_bias_test.cpp.

// The restir.* tile passes take the device's workgroup shape (lighting/frame/tile_order.h: rows
// on a CPU device such as this one, squares on a GPU), except restir.initial, whose local light
// list is the tile's and stays 8x8 on every device (lighting/restir/restir_pass.cpp). The bias and
// end-to-end tests here and in restir_bias_test.cpp run the passes in these shapes.
TEST_F(RestirGpuTest, TilePassesTakeTheDevicesShapeAndInitialStaysSquare) {
  const glm::uvec2 shape = lighting::pixel_group_shape(lighting::is_cpu_device(device.info()));
  const std::array<std::uint32_t, 3> device_shape{shape.x, shape.y, 1};
  const std::array<std::uint32_t, 3> square{gpu::kPixelGroupGpuSide, gpu::kPixelGroupGpuSide, 1};
  for (const char* stage : {"temporal", "spatial", "shade"}) {
    EXPECT_EQ(lighting::RestirPass(device, shaders, stage).pipeline().local_size(), device_shape)
        << stage;
  }
  EXPECT_EQ(lighting::RestirPass(device, shaders, "initial").pipeline().local_size(), square);
  EXPECT_EQ(lighting::RestirPass(device, shaders, "restir.initial_rays", "initial", "closestemit")
                .pipeline()
                .local_size(),
            square);
  EXPECT_EQ(lighting::RestirPass(device, shaders, "restir.shade", "shade", "hostemit")
                .pipeline()
                .local_size(),
            device_shape);
}

// relMSE of a ReSTIR run along cornell_lights' "dolly" path, frames 8..11 against baseline
// references of the same (frozen) snapshots.
TEST_F(RestirGpuTest, TemporalReuseLowersErrorOnAMovingPath) {
  World world(cornell(), {.threads = 1, .seed = 1, .fixed_dt = 1.0 / 30.0,
                          .aspect = float(kW) / float(kH)});
  world.set_camera_path("dolly");
  std::vector<FrameSnapshot> path;
  for (int f = 0; f < 12; ++f) path.push_back(world.step());
  std::vector<ImageRGBA32F> refs;
  for (int f = 8; f < 12; ++f) refs.push_back(baseline_mean(cornell(), path[f], 256));

  double error[2] = {0.0, 0.0};
  for (int temporal = 0; temporal < 2; ++temporal) {
    RenderHarness h(device, shaders, cornell(),
                    test::make_restir(device, shaders, {{"temporal", temporal ? "on" : "off"}}),
                    kW, kH);
    for (int f = 0; f < 12; ++f) {
      const ImageRGBA32F img = h.render(path[f]);
      if (f >= 8) error[temporal] += runtime::relative_mse(img, refs[f - 8]) / 4.0;
    }
  }
  std::printf("[restir temporal] relMSE without temporal %.4f, with %.4f (ratio %.2f)\n", error[0],
              error[1], error[0] / error[1]);
  EXPECT_LT(error[1], error[0]) << "temporal reuse must lower relMSE on a moving camera";
}

// Visibility reuse (visibility_reuse = 4) shades with the verdicts its history recorded: over a
// still camera and still geometry they are the shadow rays' own, so every frame equals the run
// without reuse bit for bit (same seed, same reservoirs); when an occluder moves, the reused
// verdicts lag, so the frames differ (the reuse path is really taken).
TEST_F(RestirGpuTest, VisibilityReuseIsExactOverStillGeometryAndLagsWhenItMoves) {
  const FrameSnapshot first = test::first_snapshot(cornell(), kW, kH);
  for (const bool move : {false, true}) {
    std::vector<ImageRGBA32F> images[2];
    for (int reuse = 0; reuse < 2; ++reuse) {
      RenderHarness h(device, shaders, cornell(),
                      test::make_restir(device, shaders,
                                        {{"visibility_reuse", reuse ? "4" : "0"}}),
                      kW, kH);
      FrameSnapshot s = first;
      for (int f = 0; f < 8; ++f) {
        images[reuse].push_back(h.render(s));
        s = frozen(s);
        if (!move) continue;
        for (SnapshotInstance& inst : s.instances) {
          if (cornell()->instances[inst.stable_id].name != "tall_box") continue;
          inst.prev_object_to_world = inst.object_to_world;
          inst.object_to_world =
              glm::translate(glm::mat4(1.0f), glm::vec3(0.08f, 0.0f, 0.0f)) * inst.object_to_world;
        }
      }
    }
    std::size_t differing = 0;
    for (int f = 0; f < 8; ++f) {
      ASSERT_EQ(images[1][f].count_non_finite(), 0u);
      differing += images[0][f].pixels != images[1][f].pixels ? 1 : 0;
    }
    if (move) {
      EXPECT_GT(differing, 0u) << "a moving occluder must show the reused (stale) verdicts";
    } else {
      EXPECT_EQ(differing, 0u) << "still geometry: reused verdicts equal the rays' own";
    }
  }
}

// restir.temporal's per-pixel status as the disocclusion debug view shows it (shared/restir.h:
// red = kRestirStatusNoHistory, green = reprojected, yellow = a retry matched, black = sky).
enum class Status { Sky, NoHistory, History };
std::vector<Status> temporal_status(const ImageRGBA32F& debug) {
  std::vector<Status> status(debug.pixels.size() / 4);
  for (std::size_t p = 0; p < status.size(); ++p) {
    const float r = debug.pixels[4 * p], g = debug.pixels[4 * p + 1];
    status[p] = r == 0.0f && g == 0.0f ? Status::Sky
                : r == 1.0f && g == 0.0f ? Status::NoHistory
                                         : Status::History;
  }
  return status;
}

// Judged by geometry, not by ReSTIR: pixel p of frame t reprojects to q = p + 0.5 + motion
// (shared/gbuffer.h) in frame t-1. `newly_visible`: p shows a surface other than `occluder` at t
// while every pixel within 2 px of q showed `occluder` at t-1 (2 px covers restir.temporal's
// retries within 1.5 px, so no history pixel holds the surface p now shows). `still_visible`: p
// and every pixel within 2 px of q show the same instance (not the occluder) in both frames.
struct GeometryMasks {
  std::vector<std::uint8_t> newly_visible;
  std::vector<std::uint8_t> still_visible;
};
GeometryMasks geometry_masks(const lighting::GBufferTexels& previous,
                             const lighting::GBufferTexels& current, std::uint32_t occluder) {
  constexpr int kRadius = 2;
  GeometryMasks m{std::vector<std::uint8_t>(std::size_t{kW} * kH, 0),
                  std::vector<std::uint8_t>(std::size_t{kW} * kH, 0)};
  for (int y = 0; y < int(kH); ++y)
    for (int x = 0; x < int(kW); ++x) {
      const std::size_t p = std::size_t(y) * kW + std::size_t(x);
      const std::uint32_t now = current.ids[p].x;
      if (now == gpu::kNoInstance || now == occluder) continue;
      const glm::vec2 q = glm::vec2(float(x), float(y)) + 0.5f + glm::vec2(current.motion[p]);
      const int qx = int(std::floor(q.x)), qy = int(std::floor(q.y));
      if (qx < kRadius || qy < kRadius || qx + kRadius >= int(kW) || qy + kRadius >= int(kH))
        continue;
      bool all_occluder = true, all_same = true;
      for (int dy = -kRadius; dy <= kRadius; ++dy)
        for (int dx = -kRadius; dx <= kRadius; ++dx) {
          const std::uint32_t before = previous.ids[std::size_t(qy + dy) * kW + std::size_t(qx + dx)].x;
          all_occluder = all_occluder && before == occluder;
          all_same = all_same && before == now;
        }
      m.newly_visible[p] = all_occluder ? 1 : 0;
      m.still_visible[p] = all_same ? 1 : 0;
    }
  return m;
}

std::size_t tall_box_index(const Level& level) {
  for (std::size_t i = 0; i < level.instances.size(); ++i)
    if (level.instances[i].name == "tall_box") return i;
  throw RuntimeError("cornell_lights has no tall_box");
}

// (3a) Disocclusion judged by geometry: the camera moves along cornell_lights' dolly and at frame
// t0 the tall box is moved far behind the camera. The newly visible pixels (wall at t0, box at
// t0-1 around the reprojected position, from the read-back instance ids and motion vectors) must
// get no history: >= 99% of them kRestirStatusNoHistory. And the still-visible pixels (same
// instance around the reprojected position) must keep theirs: >= 95% reuse (a predicate that
// rejects everything would pass the first check). Power: accepting every valid neighbour in
// restir_surfaces_similar gives the newly visible pixels history (measured: see the printout).
TEST_F(RestirGpuTest, DisocclusionJudgedByGeometry) {
  const std::size_t box = tall_box_index(*cornell());
  World world(cornell(), {.threads = 1, .seed = 1, .fixed_dt = 1.0 / 30.0,
                          .aspect = float(kW) / float(kH)});
  world.set_camera_path("dolly");
  constexpr int kT0 = 6;
  RenderHarness run(device, shaders, cornell(),
                    test::make_restir(device, shaders, {{"debug_view", "disocclusion"}}), kW, kH);
  lighting::GBufferTexels previous, current;
  ImageRGBA32F debug;
  for (int f = 0; f <= kT0; ++f) {
    FrameSnapshot s = world.step();
    ASSERT_EQ(s.instances[box].stable_id, box);
    if (f == kT0) {
      s.instances[box].object_to_world =
          glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 50.0f)) *
          s.instances[box].object_to_world;
    }
    previous = current;
    debug = run.render(s, &current);
  }
  const GeometryMasks masks = geometry_masks(previous, current, std::uint32_t(box));
  const std::vector<Status> status = temporal_status(debug);
  std::size_t newly = 0, newly_no_history = 0, still = 0, still_history = 0;
  for (std::size_t p = 0; p < status.size(); ++p) {
    if (masks.newly_visible[p]) {
      ++newly;
      newly_no_history += status[p] == Status::NoHistory ? 1 : 0;
    }
    if (masks.still_visible[p]) {
      ++still;
      still_history += status[p] == Status::History ? 1 : 0;
    }
  }
  std::printf("[restir disocclusion] geometry: %zu newly visible pixels, %zu with no history; "
              "%zu still visible, %zu reusing history\n",
              newly, newly_no_history, still, still_history);
  ASSERT_GT(newly, 50u) << "the box must uncover part of the room";
  ASSERT_GT(still, 1000u);
  EXPECT_GE(double(newly_no_history), 0.99 * double(newly))
      << "newly visible pixels must not reuse the occluder's history";
  EXPECT_GE(double(still_history), 0.95 * double(still))
      << "pixels whose surface stayed visible must reuse history";
}

// (3b) The same occluder leaves a static view at frame t0: the wall pixels it uncovers (by
// geometry, as above) get back within 2x of their steady-state relMSE within 4 frames, without a
// dark or bright smear (masked mean within 5% of the reference).
TEST_F(RestirGpuTest, DisocclusionRecoversWithinFourFrames) {
  const FrameSnapshot first = test::first_snapshot(cornell(), kW, kH);
  const std::size_t box = tall_box_index(*cornell());
  ASSERT_EQ(first.instances[box].stable_id, box);
  // Frames 0..t0-1: box in place; from t0: box moved far behind the camera.
  constexpr int kT0 = 12;
  constexpr int kFrames = kT0 + 30;
  std::vector<FrameSnapshot> frames;
  FrameSnapshot s = first;
  for (int f = 0; f < kFrames; ++f) {
    if (f > 0) s = frozen(s);
    if (f == kT0) {
      s.instances[box].object_to_world =
          glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 50.0f)) *
          s.instances[box].object_to_world;
    }
    frames.push_back(s);
  }
  const ImageRGBA32F reference = baseline_mean(cornell(), frozen(frames.back()), 512);

  RenderHarness run(device, shaders, cornell(), test::make_restir(device, shaders, {}), kW, kH);
  std::vector<ImageRGBA32F> images;
  lighting::GBufferTexels before, after;
  for (int f = 0; f < kFrames; ++f) {
    lighting::GBufferTexels* ids = f == kT0 - 1 ? &before : f == kT0 ? &after : nullptr;
    images.push_back(run.render(frames[f], ids));
  }
  const std::vector<std::uint8_t> mask =
      geometry_masks(before, after, std::uint32_t(box)).newly_visible;
  const std::size_t newly_visible = test::count(mask);
  ASSERT_GT(newly_visible, 50u) << "the box must uncover part of the wall";
  double steady = 0.0;
  for (int f = kFrames - 5; f < kFrames; ++f)
    steady += runtime::relative_mse(images[f], reference, mask) / 5.0;
  const double ref_mean = test::masked_mean(reference, mask);
  std::printf("[restir disocclusion] %zu newly visible pixels, steady relMSE %.4f\n",
              newly_visible, steady);
  for (int f = kT0; f < kT0 + 4; ++f) {
    const double e = runtime::relative_mse(images[f], reference, mask);
    const double m = test::masked_mean(images[f], mask) / ref_mean - 1.0;
    std::printf("[restir disocclusion] frame t0+%d relMSE %.4f (%.2fx steady) mean %+.2f%%\n",
                f - kT0, e, e / steady, 100.0 * m);
    EXPECT_LT(std::abs(m), 0.05) << "frame t0+" << f - kT0 << ": smear (masked mean off by >5%)";
  }
  EXPECT_LT(runtime::relative_mse(images[kT0 + 3], reference, mask), 2.0 * steady)
      << "within 4 frames the newly visible pixels must be back within 2x of steady state";
}

// A floor under point light B at (1, 2, 0), with the light objects `before` (JSON, each followed
// by a comma; none: "") listed ahead of B, so they take the lower light indices.
std::string floor_lit_by_b(const std::string& before) {
  return R"({
    "materials": { "white": { "base_color": [0.7, 0.7, 0.7], "roughness": 0.8 } },
    "primitives": [ { "type": "plane", "name": "floor", "size": [4, 4], "material": "white" } ],
    "lights": [ )" + before + R"(
      { "type": "point", "name": "b", "position": [1, 2, 0], "intensity": 2 } ],
    "camera": { "position": [0, 3, 3], "target": [0, 0, 0], "yfov_deg": 60 } })";
}

// One MIS mode, with restir.temporal's neighbours from last frame in place of the spatial pass
// where `temporal_neighbours` is not "0".
struct ReuseConfig {
  const char* mode;
  const char* temporal_neighbours;
  bool fused() const { return std::string(temporal_neighbours) != "0"; }
  std::vector<std::pair<std::string, std::string>> settings() const {
    return {{"bias_correction", mode},
            {"temporal_neighbours", temporal_neighbours},
            {"spatial_passes", fused() ? "0" : "1"}};
  }
};

// Two lights: A (a bright spot on the floor's left half) first in the light list, B (a dim point
// light) second. A is removed at frame 6: from then the image must equal the B-only image (B
// alone is sampled exactly, W = 1, so the comparison is tight: 0.1% on the mean, 1e-3 per
// pixel), in every bias mode and with restir.temporal's neighbours from last frame. The frame of
// the removal reuses no history (RestirIntegrator: a removed light's share still weighs in every
// history W); frames 7..9 reuse frame 6's, where B is already index 0. The remap itself:
// InsertedLightRemapsEveryHistoryDomain.
TEST_F(RestirGpuTest, RemovedLightContributesNothingNextFrame) {
  auto level = test::level_from_json(
      "two_lights", floor_lit_by_b(R"({ "type": "spot", "name": "a", "position": [-1, 2, 0],
        "target": [-1, 0, 0], "intensity": 400, "inner_cone_deg": 20, "outer_cone_deg": 30 },)"));
  auto level_b = test::level_from_json("light_b", floor_lit_by_b(""));
  ASSERT_EQ(level->lights.size(), 2u);
  const FrameSnapshot first = test::first_snapshot(level, kW, kH);
  ASSERT_EQ(first.lights.size(), 2u);

  RenderHarness only_b(device, shaders, level_b, test::make_restir(device, shaders, {}), kW, kH);
  const ImageRGBA32F b = only_b.render(test::first_snapshot(level_b, kW, kH));
  const double mean_b = runtime::mean_rgb(b);
  // Each bias mode, and restir.temporal's neighbours from last frame (after the removal the
  // frame reuses no history; from frame 7 five or more domains must still weigh B's exact W = 1
  // sample to exactly 1).
  for (const ReuseConfig& c : {ReuseConfig{"pairwise", "0"}, ReuseConfig{"balance", "0"},
                               ReuseConfig{"none", "0"}, ReuseConfig{"pairwise", "4"}}) {
    const std::string mode = std::string(c.mode) + (c.fused() ? "+tn" : "");
    RenderHarness run(device, shaders, level, test::make_restir(device, shaders, c.settings()),
                      kW, kH);
    FrameSnapshot s = first;
    std::vector<ImageRGBA32F> images;
    for (int f = 0; f < 10; ++f) {
      if (f > 0) s = frozen(s);
      if (f == 6) s.lights.erase(s.lights.begin());  // remove A (stable id 0)
      images.push_back(run.render(s));
    }
    const double mean_a = runtime::mean_rgb(images[5]);
    std::printf("[restir light removal] %-11s mean with A %.5f, B only %.5f, after removal:",
                mode.c_str(), mean_a, mean_b);
    for (int f = 6; f < 10; ++f) std::printf(" %.5f", runtime::mean_rgb(images[f]));
    std::printf("\n");
    ASSERT_GT(mean_a, 20.0 * mean_b) << "A must dominate before it is removed";
    for (int f = 6; f < 10; ++f) {
      EXPECT_NEAR(runtime::mean_rgb(images[f]), mean_b, 1e-3 * mean_b) << mode << " frame " << f;
      double max_diff = 0.0;
      for (std::size_t i = 0; i < b.pixels.size(); ++i)
        max_diff = std::max(max_diff, double(std::abs(images[f].pixels[i] - b.pixels[i])));
      EXPECT_LT(max_diff, 1e-3) << mode << " frame " << f << ": per pixel, the B-only image";
    }
  }
}

// A light inserted in front of the list: C (a point light under the floor, which lights none of
// it) comes back at frame 6 as index 0, so B moves 0 -> 1 and every history sample must reach it
// through light_previous_to_current (an inserted light does not stop reuse, a removed one does).
// A history domain that kept the old index would name C, whose p̂ on the floor is 0, while its M
// still claims most of the weight: the frame would go dark. Frames 6..9 must keep B's mean (B
// alone is exact, W = 1; with C drawn as often as B the candidates' count of B varies: 1%,
// measured within 0.06%), with the reprojected pixel alone and with 4 of last frame's neighbours
// (each its own domain, each remapped), in pairwise and balance MIS.
TEST_F(RestirGpuTest, InsertedLightRemapsEveryHistoryDomain) {
  auto level = test::level_from_json(
      "c_and_b", floor_lit_by_b(R"({ "type": "point", "name": "c", "position": [0, -1, 0],
        "intensity": 2 },)"));
  auto level_b = test::level_from_json("light_b", floor_lit_by_b(""));
  const FrameSnapshot both = test::first_snapshot(level, kW, kH);
  ASSERT_EQ(both.lights.size(), 2u);
  ASSERT_EQ(both.lights[0].stable_id, 0u) << "C first";
  FrameSnapshot only_b_first = both;
  only_b_first.lights.erase(only_b_first.lights.begin());

  RenderHarness b_run(device, shaders, level_b, test::make_restir(device, shaders, {}), kW, kH);
  const double mean_b = runtime::mean_rgb(b_run.render(test::first_snapshot(level_b, kW, kH)));
  for (const ReuseConfig& c : {ReuseConfig{"pairwise", "0"}, ReuseConfig{"pairwise", "4"},
                               ReuseConfig{"balance", "4"}}) {
    RenderHarness run(device, shaders, level, test::make_restir(device, shaders, c.settings()),
                      kW, kH);
    FrameSnapshot s = only_b_first;
    std::printf("[restir light insertion] %-8s neighbours %s, B only %.5f:", c.mode,
                c.temporal_neighbours, mean_b);
    for (int f = 0; f < 10; ++f) {
      if (f > 0) s = frozen(s);
      if (f == 6) s.lights = both.lights;  // C back, in front of B (the view is still)
      const ImageRGBA32F image = run.render(s);
      EXPECT_TRUE(test::all_finite(image));
      const double mean = runtime::mean_rgb(image);
      std::printf(" %.5f", mean);
      if (f < 6) {
        EXPECT_NEAR(mean, mean_b, 1e-3 * mean_b) << c.mode << " frame " << f << ": B alone";
      } else {
        EXPECT_NEAR(mean, mean_b, 0.01 * mean_b)
            << c.mode << " neighbours " << c.temporal_neighbours << " frame " << f;
      }
    }
    std::printf("\n");
  }
}

// restir.temporal's neighbours from last frame (temporal_neighbours, RestirSettings), read through
// the M debug view (M / M cap, shared/restir.h) on a still view of cornell_lights without spatial
// passes. Frame 0 has no history: M is the 8 candidates everywhere, with or without neighbours.
// Frame 1 merges the reprojected pixel (M 8 + 8) and, with 4 neighbours, up to 4 more of last
// frame's pixels (M up to 8 + 5 x 8; a still view reprojects every pixel onto itself, so no
// disocclusion_boost): never below the run without, never above that bound, and,
// within a radius of 3 pixels, above it on most surface pixels (a neighbour fails off the image,
// on another surface or where it rounds to the reprojected pixel itself; at the default 16 pixels
// the depth test turns away most of those on the floor, ceiling and side walls, as it does for
// restir.spatial's).
TEST_F(RestirGpuTest, TemporalNeighboursMergeLastFramesNeighbours) {
  const FrameSnapshot first = test::first_snapshot(cornell(), kW, kH);
  auto run = [&](const char* neighbours) {
    RenderHarness h(device, shaders, cornell(),
                    test::make_restir(device, shaders,
                                      {{"spatial_passes", "0"},
                                       {"temporal_neighbours", neighbours},
                                       {"radius", "3"},
                                       {"debug_view", "m"}}),
                    kW, kH);
    std::vector<ImageRGBA32F> frames{h.render(first)};
    frames.push_back(h.render(frozen(first)));
    return frames;
  };
  const std::vector<ImageRGBA32F> alone = run("0"), merged = run("4");
  const float m_cap = 20.0f * 8.0f;  // balanced: m_cap 20 x 8 light candidates
  EXPECT_EQ(merged[0].pixels, alone[0].pixels) << "no history: no neighbour either";
  std::size_t surface = 0, more = 0, below = 0, above_bound = 0;
  for (std::size_t p = 0; p < std::size_t{kW} * kH; ++p) {
    const float m_alone = alone[1].pixels[4 * p] * m_cap;
    const float m_merged = merged[1].pixels[4 * p] * m_cap;
    if (m_alone == 0.0f) continue;  // sky
    ++surface;
    below += m_merged < m_alone - 1e-3f ? 1 : 0;
    above_bound += m_merged > 8.0f + 5.0f * 8.0f + 1e-3f ? 1 : 0;
    more += m_merged > m_alone + 1e-3f ? 1 : 0;
  }
  std::printf("[restir temporal neighbours] %zu surface pixels: %zu merged more history, %zu "
              "less, %zu above 5 domains\n",
              surface, more, below, above_bound);
  ASSERT_GT(surface, 2000u);
  EXPECT_EQ(below, 0u) << "neighbours only add domains";
  EXPECT_EQ(above_bound, 0u) << "at most the reprojected pixel and 4 neighbours";
  EXPECT_GT(double(more), 0.9 * double(surface)) << "a still view finds most neighbours";
}

// One reservoir per 2x2 pixels at an odd size (95x53: the last column and row of cells hold one
// pixel each): every pixel of a block shows its cell's reservoir in the M view (M is the cell's,
// whichever pixel reads it), and over 8 frames of a still view the pixels that one reservoir per
// pixel lights are lit too (all of the last column and row, 95% of the rest), with no NaN/Inf and
// the image mean within 5% (the unbiasedness itself: restir_bias_test.cpp's stride-2).
TEST_F(RestirGpuTest, ReservoirStrideSharesCellsAndLightsEveryPixel) {
  constexpr std::uint32_t kOddW = 95;
  constexpr std::uint32_t kOddH = 53;
  const FrameSnapshot first = test::first_snapshot(cornell(), kOddW, kOddH);
  {
    RenderHarness h(device, shaders, cornell(),
                    test::make_restir(device, shaders,
                                      {{"reservoir_stride", "2"}, {"debug_view", "m"}}),
                    kOddW, kOddH);
    h.render(first);
    const ImageRGBA32F m = h.render(frozen(first));
    std::size_t unlike = 0;
    for (std::uint32_t y = 0; y < kOddH; ++y) {
      for (std::uint32_t x = 0; x < kOddW; ++x) {
        const float* corner = m.at(x & ~1u, y & ~1u);
        const bool corner_surface = corner[0] > 0.0f;
        const bool surface = m.at(x, y)[0] > 0.0f;
        // Sky pixels show no M; a surface pixel shows its cell's.
        if (surface && corner_surface && m.at(x, y)[0] != corner[0]) ++unlike;
      }
    }
    EXPECT_EQ(unlike, 0u) << "pixels of one block read different reservoirs";
  }
  auto mean_of = [&](const char* stride) {
    RenderHarness h(device, shaders, cornell(),
                    test::make_restir(device, shaders, {{"reservoir_stride", stride}}), kOddW,
                    kOddH);
    runtime::ImageAccumulator acc;
    FrameSnapshot s = first;
    for (int f = 0; f < 8; ++f) {
      const ImageRGBA32F frame = h.render(s);
      EXPECT_EQ(frame.count_non_finite(), 0u) << "stride " << stride << " frame " << f;
      acc.add(frame);
      s = frozen(s);
    }
    return acc.mean();
  };
  const ImageRGBA32F one = mean_of("1"), two = mean_of("2");
  std::size_t lit = 0, dark = 0, edge_lit = 0, edge_dark = 0;
  double sum_one = 0.0, sum_two = 0.0;
  for (std::uint32_t y = 0; y < kOddH; ++y) {
    for (std::uint32_t x = 0; x < kOddW; ++x) {
      const float l1 = one.at(x, y)[0] + one.at(x, y)[1] + one.at(x, y)[2];
      const float l2 = two.at(x, y)[0] + two.at(x, y)[1] + two.at(x, y)[2];
      sum_one += l1;
      sum_two += l2;
      if (l1 <= 0.0f) continue;
      ++lit;
      dark += l2 <= 0.0f ? 1 : 0;
      if (x + 1 == kOddW || y + 1 == kOddH) {
        ++edge_lit;
        edge_dark += l2 <= 0.0f ? 1 : 0;
      }
    }
  }
  std::printf("[restir stride 2] %zu lit pixels, %zu dark at stride 2 (last column and row: %zu "
              "of %zu); mean %.4f vs %.4f\n",
              lit, dark, edge_dark, edge_lit, sum_two / (kOddW * kOddH),
              sum_one / (kOddW * kOddH));
  ASSERT_GT(lit, 3000u);
  ASSERT_GT(edge_lit, 50u);
  // The odd last column and row (one-pixel cells) are lit like the rest of the walls and floor.
  EXPECT_EQ(edge_dark, 0u) << "pixels of the last column or row no cell lights";
  // Pixels lit in 8 frames of one reservoir per pixel and in none of 8 shared ones: those of
  // strips one pixel wide (the gaps between the ceiling's panels, the tall box's grazing face),
  // whose cells resample for another surface in most frames (82 of 3017, 2.7%, when written);
  // a cell read from the wrong place darkens whole regions.
  EXPECT_LE(dark, lit / 20) << "pixels no cell lights";
  EXPECT_NEAR(sum_two / sum_one, 1.0, 0.05);
}

// (5) A camera cut: the frame after it reuses no history (every surface pixel "no history" in
// the disocclusion view, even with the camera unchanged), and its radiance is distributed like a
// fresh renderer's first frame. Radiance: kSeeds independent runs (distinct seeds) follow the
// dolly for 10 frames and cut back to the level camera; kSeeds fresh renderers (other seeds)
// render that view as their first frame. Per 12x9-pixel block, the mean over seeds of the cut
// frame agrees with the fresh mean within 5 standard errors (from the spread between seeds) and
// 10%; the per-pixel spread between seeds agrees within 20% (a frame that reused history has
// less: more samples behind each reservoir). Power: reusing history across the cut fails the
// status check, and where the reused history differs from the fresh view's, the spread check.
TEST_F(RestirGpuTest, CameraCutUsesNoHistory) {
  const FrameSnapshot first = test::first_snapshot(cornell(), kW, kH);
  RenderHarness debug(device, shaders, cornell(),
                      test::make_restir(device, shaders, {{"debug_view", "disocclusion"}}), kW, kH);
  auto no_history_fraction = [&](const ImageRGBA32F& img) {
    std::size_t red = 0, surface = 0;
    for (Status s : temporal_status(img)) {
      if (s == Status::Sky) continue;
      ++surface;
      red += s == Status::NoHistory ? 1 : 0;
    }
    return double(red) / double(std::max<std::size_t>(surface, 1));
  };
  FrameSnapshot s = first;
  double reused = 0.0;
  for (int f = 0; f < 4; ++f) {
    const ImageRGBA32F img = debug.render(s);
    if (f == 3) reused = 1.0 - no_history_fraction(img);
    s = frozen(s);
  }
  s.camera_cut = true;
  const double after_cut = no_history_fraction(debug.render(s));
  std::printf("[restir cut] pixels with history before the cut %.3f, no-history after %.3f\n",
              reused, after_cut);
  EXPECT_GT(reused, 0.95) << "a static view reuses history";
  EXPECT_EQ(after_cut, 1.0) << "after a cut no pixel may use history";

  // Radiance: cut from the dolly's far end to the level camera; compare with fresh renderers.
  constexpr int kSeeds = 8;
  constexpr std::uint32_t kBlock = 12, kBlockRows = 9;
  constexpr std::size_t kBlocks = (kW / kBlock) * (kH / kBlockRows);
  const std::size_t pixels = std::size_t{kW} * kH;
  // Per seed: block means; per pixel: sum and sum of squares of the luminance-like mean rgb.
  struct Stats {
    std::vector<double> block_sum = std::vector<double>(kBlocks, 0.0);
    std::vector<double> block_sum2 = std::vector<double>(kBlocks, 0.0);
    std::vector<double> pixel_sum = std::vector<double>(std::size_t{kW} * kH, 0.0);
    std::vector<double> pixel_sum2 = std::vector<double>(std::size_t{kW} * kH, 0.0);
    void add(const ImageRGBA32F& img) {
      std::vector<double> block(kBlocks, 0.0);
      for (std::size_t p = 0; p < std::size_t{kW} * kH; ++p) {
        const double v =
            (double(img.pixels[4 * p]) + img.pixels[4 * p + 1] + img.pixels[4 * p + 2]) / 3.0;
        pixel_sum[p] += v;
        pixel_sum2[p] += v * v;
        const std::size_t bx = (p % kW) / kBlock, by = (p / kW) / kBlockRows;
        block[by * (kW / kBlock) + bx] += v / double(kBlock * kBlockRows);
      }
      for (std::size_t b = 0; b < kBlocks; ++b) {
        block_sum[b] += block[b];
        block_sum2[b] += block[b] * block[b];
      }
    }
  };
  Stats cut_stats, fresh_stats;
  for (int k = 0; k < kSeeds; ++k) {
    World world(cornell(),
                {.threads = 1, .seed = 1, .fixed_dt = 0.5, .aspect = float(kW) / float(kH)});
    world.set_camera_path("dolly");
    RenderHarness run(device, shaders, cornell(), test::make_restir(device, shaders, {}), kW, kH,
                      10u + std::uint32_t(k));
    for (int f = 0; f < 10; ++f) (void)run.render(world.step());
    FrameSnapshot cut = first;
    cut.camera_cut = true;
    cut.prev_camera = world.latest()->camera;
    const ImageRGBA32F after = run.render(cut);
    ASSERT_TRUE(test::all_finite(after));
    cut_stats.add(after);
    RenderHarness fresh(device, shaders, cornell(), test::make_restir(device, shaders, {}), kW, kH,
                        100u + std::uint32_t(k));
    fresh_stats.add(fresh.render(first));
  }
  auto mean_var = [](double sum, double sum2) {
    const double m = sum / kSeeds;
    return std::pair{m, std::max(sum2 / kSeeds - m * m, 0.0) * kSeeds / (kSeeds - 1)};
  };
  double worst_z = 0.0, worst_rel = 0.0;
  for (std::size_t b = 0; b < kBlocks; ++b) {
    const auto [mc, vc] = mean_var(cut_stats.block_sum[b], cut_stats.block_sum2[b]);
    const auto [mf, vf] = mean_var(fresh_stats.block_sum[b], fresh_stats.block_sum2[b]);
    const double se = std::sqrt((vc + vf) / kSeeds);
    const double z = se > 0.0 ? (mc - mf) / se : 0.0;
    const double rel = mf > 0.0 ? mc / mf - 1.0 : 0.0;
    worst_z = std::max(worst_z, std::abs(z));
    worst_rel = std::max(worst_rel, std::abs(rel));
    EXPECT_LT(std::abs(z), 5.0) << "block " << b << ": cut mean " << mc << " fresh " << mf;
    EXPECT_LT(std::abs(rel), 0.10) << "block " << b << ": cut mean " << mc << " fresh " << mf;
  }
  double sd_cut = 0.0, sd_fresh = 0.0;
  for (std::size_t p = 0; p < pixels; ++p) {
    sd_cut += std::sqrt(mean_var(cut_stats.pixel_sum[p], cut_stats.pixel_sum2[p]).second);
    sd_fresh += std::sqrt(mean_var(fresh_stats.pixel_sum[p], fresh_stats.pixel_sum2[p]).second);
  }
  const double spread_ratio = sd_cut / sd_fresh;
  std::printf("[restir cut] %d seeds, %zu blocks: worst |z| %.2f, worst relative %.2f%%; "
              "per-pixel spread cut / fresh %.3f\n",
              kSeeds, kBlocks, worst_z, 100.0 * worst_rel, spread_ratio);
  EXPECT_NEAR(spread_ratio, 1.0, 0.2) << "the cut frame's noise must be a fresh frame's";
}

// Temporal permutation (RestirSettings::temporal_permutation) over a still view of
// cornell_lights: `denoised` (the default) renders raw output exactly as `off` does; `on` renders
// the first frame (no history) exactly as `off` and later frames differently; and it lowers the
// correlation of a pixel's error from one frame to the next (what a temporal denoiser cannot
// average away; measured 0.42 off, -0.19 on here). With the denoiser consuming the frame,
// the integrator is told so; with the denoiser off it is not.
TEST_F(RestirGpuTest, TemporalPermutationDecorrelatesFramesOnlyForTheDenoiser) {
  constexpr int kFrames = 12;
  const FrameSnapshot first = test::first_snapshot(cornell(), kW, kH);
  auto run = [&](const char* mode) {
    RenderHarness h(device, shaders, cornell(),
                    test::make_restir(device, shaders, {{"temporal_permutation", mode}}), kW, kH,
                    7u);
    std::vector<ImageRGBA32F> frames;
    FrameSnapshot s = first;
    for (int f = 0; f < kFrames; ++f) {
      frames.push_back(h.render(s));
      EXPECT_TRUE(test::all_finite(frames.back())) << mode << " frame " << f;
      s = frozen(s);
    }
    return frames;
  };
  const std::vector<ImageRGBA32F> off = run("off"), on = run("on"), by_default = run("denoised");
  for (int f = 0; f < kFrames; ++f) {
    EXPECT_EQ(by_default[f].pixels, off[f].pixels) << "raw output, frame " << f;
    if (f == 0) {
      EXPECT_EQ(on[f].pixels, off[f].pixels) << "the first frame has no history";
    } else {
      EXPECT_NE(on[f].pixels, off[f].pixels) << "frame " << f;
    }
  }
  // Lag-1 correlation over pixels and frames 2..11 of each pixel's deviation from its own mean
  // over those frames (mean rgb).
  auto lag_one_correlation = [&](const std::vector<ImageRGBA32F>& frames) {
    const std::size_t n = std::size_t{kW} * kH;
    auto value = [&](int f, std::size_t p) {
      const float* px = &frames[f].pixels[4 * p];
      return (double(px[0]) + px[1] + px[2]) / 3.0;
    };
    double product = 0.0, square = 0.0;
    for (std::size_t p = 0; p < n; ++p) {
      double mean = 0.0;
      for (int f = 2; f < kFrames; ++f) mean += value(f, p) / (kFrames - 2);
      for (int f = 2; f < kFrames; ++f) {
        const double d = value(f, p) - mean;
        square += d * d;
        if (f + 1 < kFrames) product += d * (value(f + 1, p) - mean);
      }
    }
    return square > 0.0 ? product / square : 0.0;
  };
  const double correlation_off = lag_one_correlation(off);
  const double correlation_on = lag_one_correlation(on);
  std::printf("[restir permutation] frame-to-frame error correlation: off %.3f, on %.3f\n",
              correlation_off, correlation_on);
  EXPECT_LT(correlation_on, correlation_off - 0.15);

  RenderHarness h(device, shaders, cornell(), test::make_restir(device, shaders, {}), kW, kH);
  h.renderer().set_output(lighting::FrameOutput::Denoised);
  (void)h.render(first);
  EXPECT_TRUE(h.renderer().last_inputs().denoised);
  lighting::DenoiseSettings no_denoiser = h.renderer().denoise_settings();
  no_denoiser.enabled = false;
  h.renderer().set_denoise_settings(no_denoiser);
  (void)h.render(frozen(first));
  EXPECT_FALSE(h.renderer().last_inputs().denoised) << "the denoiser is off: raw is shown";
}

// bsdf_min_gloss gives BSDF candidates to the glossy surfaces only, pixel by pixel, and a level
// whose glossiest material stays below it draws none. Without reuse (each pixel shows its own
// initial reservoir) cornell_lights' glossy box (roughness 0.25: gloss 0.375) matches the run
// with candidates on every surface bit for bit, its rough walls (0.1) the run without any (to
// float rounding: the frame then runs restir.initial's host-hit variant), and a gate above 0.375
// leaves the frame exactly the one without candidates.
TEST_F(RestirGpuTest, BsdfCandidatesOnlyOnGlossySurfaces) {
  const FrameSnapshot first = test::first_snapshot(cornell(), kW, kH);
  auto run = [&](std::vector<std::pair<std::string, std::string>> settings, float* max_gloss) {
    settings.insert(settings.end(), {{"temporal", "off"}, {"spatial_passes", "0"}});
    RenderHarness h(device, shaders, cornell(), test::make_restir(device, shaders, settings), kW,
                    kH, 5u);
    ImageRGBA32F image = h.render(first);
    if (max_gloss != nullptr) *max_gloss = h.renderer().last_inputs().max_gloss;
    EXPECT_TRUE(test::all_finite(image));
    return image;
  };
  float max_gloss = 0.0f;
  const ImageRGBA32F none = run({}, &max_gloss);
  const ImageRGBA32F everywhere = run({{"bsdf_candidates", "1"}}, nullptr);
  const ImageRGBA32F glossy = run({{"bsdf_candidates", "1"}, {"bsdf_min_gloss", "0.3"}}, nullptr);
  const ImageRGBA32F gated = run({{"bsdf_candidates", "1"}, {"bsdf_min_gloss", "0.4"}}, nullptr);
  EXPECT_NEAR(max_gloss, 0.375f, 1e-6f) << "cornell_lights' glossy box";
  EXPECT_EQ(gated.pixels, none.pixels) << "no surface reaches 0.4: no BSDF candidate";
  std::size_t like_everywhere = 0, like_none = 0, neither = 0;
  for (std::size_t p = 0; p < std::size_t{kW} * kH; ++p) {
    bool same_everywhere = true, close_to_none = true;
    for (int c = 0; c < 3; ++c) {
      const float v = glossy.pixels[4 * p + c];
      same_everywhere = same_everywhere && v == everywhere.pixels[4 * p + c];
      const float n = none.pixels[4 * p + c];
      close_to_none = close_to_none && std::abs(v - n) <= 1e-5f * std::max(1.0f, std::abs(n));
    }
    const bool differ = everywhere.pixels[4 * p] != none.pixels[4 * p];
    if (!differ) continue;  // both runs agree: nothing to tell apart
    like_everywhere += same_everywhere && !close_to_none;
    like_none += close_to_none && !same_everywhere;
    neither += !same_everywhere && !close_to_none;
  }
  std::printf("[restir bsdf_min_gloss] pixels as with candidates everywhere %zu, as without %zu, "
              "neither %zu\n",
              like_everywhere, like_none, neither);
  EXPECT_EQ(neither, 0u);
  EXPECT_GT(like_everywhere, 50u) << "the glossy box";
  EXPECT_GT(like_none, 500u) << "the walls";
}

// The lower history cap where points move (m_cap_moving, restir_history_m_cap in
// shared/restir.h) reaches only frames the denoiser consumes, and there only points that move:
// along cornell_lights' dolly path raw frames are the same bit for bit with 0.25 and with 1 (off),
// and so are denoised frames of a still view; denoised frames of the dolly differ once the
// history has grown past the lower cap.
TEST_F(RestirGpuTest, MovingPointsCapActsOnlyWhereTheDenoiserSeesMotion) {
  constexpr int kFrames = 8;
  World world(cornell(),
              {.threads = 1, .seed = 1, .fixed_dt = 1.0 / 30.0, .aspect = float(kW) / float(kH)});
  world.set_camera_path("dolly");
  std::vector<FrameSnapshot> dolly;
  for (int f = 0; f < kFrames; ++f) dolly.push_back(world.step());
  std::vector<FrameSnapshot> still{dolly[0]};
  for (int f = 1; f < kFrames; ++f) still.push_back(frozen(still.back()));
  auto run = [&](const std::vector<FrameSnapshot>& path, const char* fraction, bool denoised) {
    RenderHarness h(device, shaders, cornell(),
                    test::make_restir(device, shaders, {{"m_cap_moving", fraction}}), kW, kH);
    if (denoised) h.renderer().set_output(lighting::FrameOutput::Denoised);
    std::vector<ImageRGBA32F> frames;
    for (const FrameSnapshot& s : path) {
      frames.push_back(h.render(s));
      EXPECT_TRUE(test::all_finite(frames.back())) << fraction;
    }
    return frames;
  };
  const auto raw_on = run(dolly, "0.25", false), raw_off = run(dolly, "1", false);
  const auto still_on = run(still, "0.25", true), still_off = run(still, "1", true);
  const auto moving_on = run(dolly, "0.25", true), moving_off = run(dolly, "1", true);
  int moving_differ = 0;
  for (int f = 0; f < kFrames; ++f) {
    EXPECT_EQ(raw_on[f].pixels, raw_off[f].pixels) << "raw frame " << f;
    EXPECT_EQ(still_on[f].pixels, still_off[f].pixels) << "denoised still frame " << f;
    moving_differ += moving_on[f].pixels != moving_off[f].pixels;
  }
  EXPECT_EQ(moving_on[0].pixels, moving_off[0].pixels) << "the first frame has no history";
  EXPECT_NE(moving_on[kFrames - 1].pixels, moving_off[kFrames - 1].pixels);
  std::printf("[restir moving cap] %d of %d denoised dolly frames differ\n", moving_differ,
              kFrames);
}

// NaN/Inf in: a light with infinite intensity and one at a NaN position next to a normal one.
// Nothing non-finite reaches the output (radiance and the W/M debug views, which show the
// reservoirs' contents), and the normal light still lights the scene as it does alone.
TEST_F(RestirGpuTest, NonFiniteLightsNeverReachReservoirsOrOutput) {
  const std::string json = R"({
    "materials": { "white": { "base_color": [0.7, 0.7, 0.7], "roughness": 0.8 } },
    "primitives": [ { "type": "plane", "name": "floor", "size": [4, 4], "material": "white" } ],
    "lights": [
      { "type": "point", "name": "inf", "position": [-1, 2, 0], "intensity": 1 },
      { "type": "point", "name": "nan", "position": [0, 2, 0], "intensity": 1 },
      { "type": "point", "name": "good", "position": [1, 2, 0], "intensity": 2 } ],
    "camera": { "position": [0, 3, 3], "target": [0, 0, 0], "yfov_deg": 60 } })";
  auto level = test::level_from_json("bad_lights", json);
  FrameSnapshot s = test::first_snapshot(level, kW, kH);
  ASSERT_EQ(s.lights.size(), 3u);
  s.lights[0].intensity = std::numeric_limits<float>::infinity();
  s.lights[1].position = glm::vec3(std::numeric_limits<float>::quiet_NaN());
  FrameSnapshot good = s;
  good.lights[0].intensity = 0.0f;
  good.lights[1].intensity = 0.0f;
  good.lights[1].position = glm::vec3(0.0f, 2.0f, 0.0f);

  for (const char* view : {"none", "w", "m"}) {
    RenderHarness run(device, shaders, level,
                      test::make_restir(device, shaders, {{"debug_view", view}}), kW, kH);
    FrameSnapshot f = s;
    for (int k = 0; k < 4; ++k) {
      const ImageRGBA32F img = run.render(f);
      ASSERT_TRUE(test::all_finite(img)) << view << " frame " << k;
      f = frozen(f);
    }
  }
  RenderHarness bad_run(device, shaders, level, test::make_restir(device, shaders, {}), kW, kH);
  RenderHarness good_run(device, shaders, level, test::make_restir(device, shaders, {}), kW, kH);
  ImageRGBA32F bad_img, good_img;
  FrameSnapshot fb = s, fg = good;
  for (int k = 0; k < 4; ++k) {
    bad_img = bad_run.render(fb);
    good_img = good_run.render(fg);
    fb = frozen(fb);
    fg = frozen(fg);
  }
  const double bad_mean = runtime::mean_rgb(bad_img);
  const double good_mean = runtime::mean_rgb(good_img);
  std::printf("[restir nan] mean with Inf/NaN lights %.5f, good light alone %.5f\n", bad_mean,
              good_mean);
  EXPECT_GT(good_mean, 0.0);
  // The Inf light either never gets picked (zero alias weight) or is dropped by the guards; the
  // good light must keep lighting the floor as it does alone (within 5%).
  EXPECT_NEAR(bad_mean, good_mean, 0.05 * good_mean);
}

}  // namespace
}  // namespace lantern
