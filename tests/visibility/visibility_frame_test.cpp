// The ray-query backend in the frame: every tracing integrator (baseline, reference, restir with
// its fixed seed) renders cornell_lights (an orbiting box: the TLAS is rebuilt by
// scene.tlas_build every frame) at 64x36 with --set visibility=bvh and =rayquery, and the
// frames agree: each channel's mean within 0.1%, and >= 99.9% of the pixels equal to float noise
// (relative 1e-4). The same for --set visibility=host (Embree answers restir.shade's and the
// baseline's shadow rays in the host pass visibility.host, and restir.initial's BSDF candidates'
// closest hits in visibility.host_closest). Synchronization validation is on and must stay clean.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/level/level_loader.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/frame/headless_session.h"
#include "runtime/gpu/shader_library.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {

using lighting::VisibilityBackend;
using lighting::VisibilitySetting;

constexpr std::uint32_t kWidth = 64;
constexpr std::uint32_t kHeight = 36;
constexpr std::uint32_t kFrames = 4;

runtime::DeviceOptions sync_validated() {
  runtime::DeviceOptions o = runtime::test::test_device_options();
  o.sync_validation = true;
  return o;
}

struct Frames {
  std::vector<runtime::ImageRGBA32F> images;
  std::uint32_t tlas_builds = 0;  // frames whose passes included scene.tlas_build
  std::uint32_t host_passes = 0;  // frames whose passes included visibility.host
  std::uint32_t host_closest_passes = 0;  // ... and visibility.host_closest
  VisibilityBackend backend = VisibilityBackend::Bvh;
};

class VisibilityFrameTest : public runtime::test::GpuTest,
                            public ::testing::WithParamInterface<std::string> {
 protected:
  VisibilityFrameTest() : GpuTest(sync_validated()) {}

  // `move_fixed`: the snapshot lifts the tall box (a fixed instance, merged into the BVH's
  // world-space tree) a little more every frame, so the BVH takes it out of the merged tree
  // (rebuild and re-upload of the BLAS part) on the first frame it moves.
  Frames render(VisibilitySetting visibility, bool move_fixed = false,
                std::vector<std::pair<std::string, std::string>> settings = {}) {
    lighting::SessionOptions o;
    o.integrator.name = GetParam();
    o.integrator.settings = std::move(settings);
    o.integrator.visibility = visibility;
    if (GetParam() == "reference") o.integrator.spp = 4;
    o.width = kWidth;
    o.height = kHeight;
    o.seed = 3;
    lighting::HeadlessSession session(device, shaders_, level_, o);
    session.warm_up();
    Frames out;
    out.backend = session.renderer().scene().visibility();
    for (std::uint32_t f = 0; f < kFrames; ++f) {
      runtime::ImageRGBA32F image;
      FrameSnapshot snapshot = session.step_world();
      if (move_fixed) {
        for (SnapshotInstance& inst : snapshot.instances) {
          if (level_->instances[inst.stable_id].name != "tall_box") continue;
          const glm::mat4 lift = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.05f * f, 0.0f));
          inst.prev_object_to_world = inst.object_to_world;
          inst.object_to_world = lift * inst.object_to_world;
        }
      }
      const lighting::FrameTiming t = session.render(snapshot, &image);
      out.tlas_builds += std::any_of(t.passes.begin(), t.passes.end(),
                                     [](const auto& p) { return p.first == "scene.tlas_build"; });
      out.host_passes += std::any_of(t.passes.begin(), t.passes.end(),
                                     [](const auto& p) { return p.first == "visibility.host"; });
      out.host_closest_passes +=
          std::any_of(t.passes.begin(), t.passes.end(),
                      [](const auto& p) { return p.first == "visibility.host_closest"; });
      out.images.push_back(std::move(image));
    }
    return out;
  }

  runtime::ShaderLibrary shaders_;
  std::shared_ptr<const Level> level_ =
      std::make_shared<const Level>(load_level_argument("cornell_lights"));
};

struct Agreement {
  double max_mean_rel = 0.0;  // over R, G, B
  double equal_fraction = 0.0;
  double mean_luminance = 0.0;
};

Agreement compare(const runtime::ImageRGBA32F& a, const runtime::ImageRGBA32F& b) {
  Agreement out;
  double sum_a[3] = {0, 0, 0}, sum_b[3] = {0, 0, 0};
  std::size_t equal = 0;
  const std::size_t pixels = std::size_t{a.width} * a.height;
  for (std::size_t i = 0; i < pixels; ++i) {
    bool same = true;
    for (int c = 0; c < 3; ++c) {
      const double x = a.pixels[4 * i + c], y = b.pixels[4 * i + c];
      sum_a[c] += x;
      sum_b[c] += y;
      same = same && std::abs(x - y) <= 1e-4 * std::max(std::abs(x), std::abs(y)) + 1e-6;
    }
    equal += same ? 1 : 0;
  }
  for (int c = 0; c < 3; ++c) {
    out.max_mean_rel = std::max(out.max_mean_rel, std::abs(sum_a[c] - sum_b[c]) / sum_a[c]);
    out.mean_luminance += sum_a[c] / (3.0 * static_cast<double>(pixels));
  }
  out.equal_fraction = static_cast<double>(equal) / static_cast<double>(pixels);
  return out;
}

TEST_P(VisibilityFrameTest, RayQueryRendersTheBvhImage) {
  ASSERT_TRUE(device.caps().ray_query) << "lavapipe 25 has VK_KHR_ray_query (PLATFORM.md)";
  const Frames bvh = render(VisibilitySetting::Bvh);
  const Frames rq = render(VisibilitySetting::RayQuery);
  ASSERT_EQ(bvh.backend, VisibilityBackend::Bvh);
  ASSERT_EQ(rq.backend, VisibilityBackend::RayQuery);
  EXPECT_EQ(bvh.tlas_builds, 0u) << "the BVH scene has no TLAS to build";
  EXPECT_GE(rq.tlas_builds, kFrames - 1) << "the orbiting box moves every frame";
  for (std::uint32_t f = 0; f < kFrames; ++f) {
    const Agreement g = compare(bvh.images[f], rq.images[f]);
    EXPECT_GT(g.mean_luminance, 0.0) << "frame " << f << " is black: nothing compared";
    EXPECT_LE(g.max_mean_rel, 1e-3) << "frame " << f;
    EXPECT_GE(g.equal_fraction, 0.999) << "frame " << f;
    EXPECT_EQ(rq.images[f].count_non_finite(), 0u) << "frame " << f;
  }
  // The box moved between the first and last frame, so a TLAS left at its first placement would
  // have shown (the comparison above can fail).
  EXPECT_LT(compare(rq.images.front(), rq.images.back()).equal_fraction, 0.999);
}

TEST_P(VisibilityFrameTest, FixedInstanceMovedOutOfTheMergedTreeRendersTheRayQueryImage) {
  ASSERT_TRUE(device.caps().ray_query) << "lavapipe 25 has VK_KHR_ray_query (PLATFORM.md)";
  const Frames bvh = render(VisibilitySetting::Bvh, true);
  const Frames rq = render(VisibilitySetting::RayQuery, true);
  for (std::uint32_t f = 0; f < kFrames; ++f) {
    const Agreement g = compare(bvh.images[f], rq.images[f]);
    EXPECT_GT(g.mean_luminance, 0.0) << "frame " << f << " is black: nothing compared";
    EXPECT_LE(g.max_mean_rel, 1e-3) << "frame " << f;
    EXPECT_GE(g.equal_fraction, 0.999) << "frame " << f;
  }
  // The lifted box changes the image (its shadow moves), so stale triangles would be seen.
  EXPECT_LT(compare(bvh.images.front(), bvh.images.back()).equal_fraction, 0.99);
}

TEST_P(VisibilityFrameTest, HostRendersTheBvhImage) {
  for (const bool move_fixed : {false, true}) {
    const Frames bvh = render(VisibilitySetting::Bvh, move_fixed);
    const Frames host = render(VisibilitySetting::Host, move_fixed);
    ASSERT_EQ(host.backend, VisibilityBackend::Host);
    // The reference traces its own rays on the BVH; the real-time integrators ask the host.
    EXPECT_EQ(host.host_passes, GetParam() == "reference" ? 0u : kFrames);
    EXPECT_EQ(bvh.host_passes, 0u);
    EXPECT_EQ(host.host_closest_passes, 0u) << "no integrator draws BSDF candidates by default";
    for (std::uint32_t f = 0; f < kFrames; ++f) {
      const Agreement g = compare(bvh.images[f], host.images[f]);
      EXPECT_GT(g.mean_luminance, 0.0) << "frame " << f << " is black: nothing compared";
      EXPECT_LE(g.max_mean_rel, 1e-3) << "frame " << f << " move_fixed " << move_fixed;
      EXPECT_GE(g.equal_fraction, 0.999) << "frame " << f << " move_fixed " << move_fixed;
      EXPECT_EQ(host.images[f].count_non_finite(), 0u) << "frame " << f;
    }
    // The scene moves between the first and last frame, so stale answers would show.
    EXPECT_LT(compare(host.images.front(), host.images.back()).equal_fraction, 0.999);
  }
  if (GetParam() != "restir") return;
  // ReSTIR's visibility reuse: restir.shade_occluded writes the host's verdicts into the
  // reservoirs as restir.shade does with its own rays, so the frames that reuse them match too.
  // BSDF candidates (the quality preset's): the host traces their closest hits
  // (visibility.host_closest), restir.initial reads them, and the image is the BVH's.
  const std::vector<std::pair<std::string, std::string>> reuse{{"visibility_reuse", "2"}};
  const std::vector<std::pair<std::string, std::string>> bsdf{{"bsdf_candidates", "2"}};
  for (const auto* settings : {&reuse, &bsdf}) {
    const Frames bvh = render(VisibilitySetting::Bvh, false, *settings);
    const Frames host = render(VisibilitySetting::Host, false, *settings);
    const std::string what = settings->front().first;
    EXPECT_EQ(host.host_closest_passes, settings == &bsdf ? kFrames : 0u) << what;
    for (std::uint32_t f = 0; f < kFrames; ++f) {
      const Agreement g = compare(bvh.images[f], host.images[f]);
      EXPECT_GT(g.mean_luminance, 0.0) << what << " frame " << f << " is black";
      EXPECT_LE(g.max_mean_rel, 1e-3) << what << " frame " << f;
      EXPECT_GE(g.equal_fraction, 0.999) << what << " frame " << f;
      EXPECT_EQ(host.images[f].count_non_finite(), 0u) << what << " frame " << f;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, VisibilityFrameTest,
                         ::testing::Values("baseline", "reference", "restir"),
                         [](const auto& param_info) { return param_info.param; });

}  // namespace
}  // namespace lantern
