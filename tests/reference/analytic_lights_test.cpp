// integrators.reference's analytic lights (point and directional here; spots take the same walk)
// on the plane of reference_plane.h, against closed forms: rho/pi * I cos / d^2 times the
// KHR_lights_punctual range window for a point light, rho/pi * E cos for a directional one.
//   - Up to kReferenceAnalyticWalkMax of them are walked at every pixel and picked in proportion
//     to their unshadowed contribution: with nothing in the way and grey lights each pick adds
//     exactly the sum, so one sample per pixel is the closed form on every pixel of every frame
//     (drawing by power, as before the walk, reads a worst relative error of 35 at one sample).
//   - Behind an occluder the picks are shadowed or not: every frame of every pixel is a whole
//     number of lit picks, as many as the stratified walk can give, and the image mean over 32
//     frames is the visible lights' sum within 0.5% (pixels whose visibility changes within the
//     pixel, and those that see the occluder, left out). The stratified picks are nearly
//     deterministic (a pixel may show the same count in all 32 frames), so no per-pixel t.
//   - The walk runs only while it costs at most kReferenceAnalyticWalkPerSample lights per
//     sample: at that count one frame is the closed form, with one light more it is not.
//   - Beyond the walk's limit the power alias table draws them: expect_matches' per-pixel t-tests
//     and image mean hold over 32 frames of 8 samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>
#include <random>
#include <vector>

#include "engine/level/primitives.h"
#include "integrators/reference.h"
#include "tests/reference/reference_plane.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {

using test::kPiD;
using test::kRho;
using test::kSize;

class ReferenceAnalyticLightsTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;
};

// Direct light of grey point light `light` at plane point q (normal +Y), unshadowed.
double point_light_at(const Light& light, const glm::dvec3& q) {
  const glm::dvec3 d = glm::dvec3(light.position) - q;
  const double d2 = glm::dot(d, d);
  double window = 1.0;
  if (light.range > 0.0f) {
    const double r2 = d2 / (static_cast<double>(light.range) * light.range);
    window = std::clamp(1.0 - r2 * r2, 0.0, 1.0);
    window *= window;
  }
  const double cosine = std::max(d.y, 0.0) / std::sqrt(d2);
  return kRho / kPiD * light.intensity * light.color.x * cosine / d2 * window;
}

// `count` grey point lights over the plane's centre, a third of them with a range.
std::vector<Light> scattered_point_lights(std::size_t count, float min_height, float intensity_lo,
                                          float intensity_hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Light> lights;
  for (std::size_t i = 0; i < count; ++i) {
    Light light;
    light.type = LightType::Point;
    light.intensity = intensity_lo + (intensity_hi - intensity_lo) * u(rng);
    light.position = glm::vec3(-2.0f + 4.0f * u(rng), min_height + u(rng), -2.0f + 4.0f * u(rng));
    light.range = i % 3 == 0 ? 1.5f + 2.0f * u(rng) : 0.0f;
    lights.push_back(light);
  }
  return lights;
}

// rho/pi * E cos of a grey directional light on the plane (normal +y).
double directional_light_term(const Light& light) {
  return kRho / kPiD * light.intensity * std::max(-light.direction().y, 0.0f);
}

// The pixels of images more than 2e-4 (relative) from the unshadowed closed form of the level's
// grey point and directional lights, and the worst relative error.
struct ClosedFormCheck {
  int off = 0;
  double worst = 0.0;
  void add(const Level& level, const runtime::ImageRGBA32F& image) {
    for (std::uint32_t y = 0; y < kSize; ++y) {
      for (std::uint32_t x = 0; x < kSize; ++x) {
        const glm::dvec3 q = test::plane_point(level.camera, x, y);
        double expected = 0.0;
        for (const Light& light : level.lights) {
          expected += light.type == LightType::Directional ? directional_light_term(light)
                                                           : point_light_at(light, q);
        }
        const double error = std::abs(image.at(x, y)[0] - expected) / expected;
        worst = std::max(worst, error);
        if (error > 2e-4) ++off;
      }
    }
  }
};

TEST_F(ReferenceAnalyticLightsTest, WithoutOccludersOneSampleIsTheClosedForm) {
  Level level = test::plane_level(4.0f, 0.6f);
  level.lights = scattered_point_lights(40, 0.3f, 0.2f, 3.0f, 5);
  Light sun;
  sun.type = LightType::Directional;
  sun.intensity = 0.7f;
  sun.rotation = look_at_orientation(glm::vec3(0.0f), glm::vec3(0.3f, -1.0f, 0.2f));
  level.lights.push_back(sun);
  ASSERT_GT(directional_light_term(sun), 0.0);

  const test::Frames frames = test::render_frames(device, shaders, level, 2, 1);
  ClosedFormCheck check;
  for (const auto& image : frames.images) check.add(level, image);
  std::printf("one sample per pixel vs the closed form: worst relative error %.2e\n", check.worst);
  EXPECT_EQ(check.off, 0) << "pixels more than 2e-4 from the closed form (worst " << check.worst
                          << ")";
}

int pixels_off_the_closed_form(const Level& level, const runtime::ImageRGBA32F& image) {
  ClosedFormCheck check;
  check.add(level, image);
  return check.off;
}

// The walk runs only while it costs at most kReferenceAnalyticWalkPerSample lights per sample:
// one light more than that per sample turns it off (power draws: not exact), as many turns it on.
TEST_F(ReferenceAnalyticLightsTest, TheWalkRunsWhileItsCostPerSampleIsBounded) {
  Level level = test::plane_level(4.0f, 0.6f);
  const std::uint32_t spp = 2;
  level.lights =
      scattered_point_lights(gpu::kReferenceAnalyticWalkPerSample * spp, 0.3f, 0.2f, 3.0f, 9);
  const int walked = pixels_off_the_closed_form(
      level, test::render_frames(device, shaders, level, 1, spp).images.at(0));
  level.lights.push_back(level.lights.front());
  const int drawn = pixels_off_the_closed_form(
      level, test::render_frames(device, shaders, level, 1, spp).images.at(0));
  std::printf("%u lights: %d pixels off the closed form; one more: %d\n",
              gpu::kReferenceAnalyticWalkPerSample * spp, walked, drawn);
  EXPECT_EQ(walked, 0);
  EXPECT_GT(drawn, static_cast<int>(kSize * kSize / 2));
}

// Does the segment from q to p cross the axis-aligned box [lo, hi]? (slab test)
bool segment_hits_box(const glm::dvec3& q, const glm::dvec3& p, const glm::dvec3& lo,
                      const glm::dvec3& hi) {
  double t0 = 0.0;
  double t1 = 1.0;
  const glm::dvec3 d = p - q;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12) {
      if (q[a] < lo[a] || q[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - q[a]) / d[a];
    double tb = (hi[a] - q[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

TEST_F(ReferenceAnalyticLightsTest, BehindAnOccluderTheMeanIsTheVisibleLightsSum) {
  Level level = test::plane_level(4.0f, 0.6f);
  level.lights = scattered_point_lights(8, 1.7f, 0.5f, 2.0f, 11);
  // A 1.2 x 0.1 x 0.8 slab at height 1.1 between the lights and the plane.
  const glm::vec3 size(1.2f, 0.1f, 0.8f);
  const glm::vec3 centre(0.2f, 1.1f, -0.1f);
  level.meshes.push_back(make_box(size));
  Instance slab;
  slab.name = "slab";
  slab.mesh = 1;
  slab.transform.translation = centre;
  slab.world = slab.transform.matrix();
  level.instances.push_back(slab);
  const glm::dvec3 lo = glm::dvec3(centre - 0.5f * size);
  const glm::dvec3 hi = glm::dvec3(centre + 0.5f * size);

  // Per light, whether the plane point is lit; a pixel counts when the camera sees the plane
  // through it and no light's visibility changes between its centre and corners.
  const glm::dvec3 eye(level.camera.position);
  auto visible = [&](const glm::dvec3& q, const Light& light) {
    return !segment_hits_box(q, glm::dvec3(light.position), lo, hi);
  };
  auto clean = [&](std::uint32_t x, std::uint32_t y) {
    const glm::dvec3 c = test::plane_point(level.camera, x, y);
    if (segment_hits_box(eye, c, lo, hi)) return false;
    for (const glm::vec2 at :
         {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1), glm::vec2(1, 1)}) {
      const glm::dvec3 corner = test::plane_point(level.camera, x, y, at);
      if (segment_hits_box(eye, corner, lo, hi)) return false;
      for (const Light& light : level.lights) {
        if (visible(corner, light) != visible(c, light)) return false;
      }
    }
    return true;
  };
  int shadowed = 0;
  for (std::uint32_t y = 0; y < kSize; ++y) {
    for (std::uint32_t x = 0; x < kSize; ++x) {
      const glm::dvec3 q = test::plane_point(level.camera, x, y);
      int lit = 0;
      for (const Light& light : level.lights) lit += visible(q, light) ? 1 : 0;
      if (clean(x, y) && lit > 0 && lit < static_cast<int>(level.lights.size())) ++shadowed;
    }
  }
  ASSERT_GT(shadowed, 300) << "the slab must shadow part of the lights on many pixels";

  // With grey lights each of the n picks adds total / n or nothing, so a frame is k total / n
  // for k whole; each run of consecutive visible lights in the list takes the floor or the
  // ceiling of its share of the n picks, so k is within `runs` of n x the visible share.
  constexpr std::uint32_t kPicks = 4;
  const test::Frames frames = test::render_frames(device, shaders, level, 32, kPicks);
  int broken = 0;
  double sum_image = 0.0;
  double sum_expected = 0.0;
  for (std::uint32_t y = 0; y < kSize; ++y) {
    for (std::uint32_t x = 0; x < kSize; ++x) {
      if (!clean(x, y)) continue;
      const glm::dvec3 q = test::plane_point(level.camera, x, y);
      double total = 0.0;
      double lit = 0.0;
      int runs = 0;
      bool in_run = false;
      for (const Light& light : level.lights) {
        const double c = point_light_at(light, q);
        if (c <= 0.0) continue;
        total += c;
        const bool v = visible(q, light);
        if (v) lit += c;
        if (v && !in_run) ++runs;
        in_run = v;
      }
      ASSERT_GT(total, 0.0);
      for (const auto& image : frames.images) {
        const double k = image.at(x, y)[0] / (total / kPicks);
        const bool whole = std::abs(k - std::round(k)) < 1e-3 * kPicks;
        if (!whole || std::abs(k - kPicks * lit / total) > runs + 1e-3) {
          if (broken++ < 5) {
            std::printf("pixel (%u, %u): %.4f picks lit, visible share %.4f of %u, %d runs\n", x, y,
                        k, lit / total, kPicks, runs);
          }
        }
        sum_image += image.at(x, y)[0];
      }
      sum_expected += lit * static_cast<double>(frames.images.size());
    }
  }
  EXPECT_EQ(broken, 0) << "frames that are not whole picks of lit lights";
  std::printf("behind the slab: image mean %.5f of the visible lights' sum\n",
              sum_image / sum_expected);
  EXPECT_NEAR(sum_image / sum_expected, 1.0, 0.005);
}

TEST_F(ReferenceAnalyticLightsTest, BeyondTheWalksLimitThePowerDrawsMatch) {
  Level level = test::plane_level(4.0f, 0.6f);
  // One bright light and kReferenceAnalyticWalkMax faint ones higher up (17% of the power).
  level.lights = scattered_point_lights(gpu::kReferenceAnalyticWalkMax, 1.5f, 1e-4f, 1e-4f, 3);
  Light bright;
  bright.type = LightType::Point;
  bright.intensity = 2.0f;
  bright.position = glm::vec3(0.4f, 1.5f, -0.3f);
  level.lights.push_back(bright);
  ASSERT_GT(level.lights.size(), gpu::kReferenceAnalyticWalkMax);

  const test::Frames frames = test::render_frames(device, shaders, level, 32, 8);
  test::expect_matches(frames, [&](std::uint32_t x, std::uint32_t y) {
    const glm::dvec3 q = test::plane_point(level.camera, x, y);
    double sum = 0.0;
    for (const Light& light : level.lights) sum += point_light_at(light, q);
    return sum;
  });
}

}  // namespace
}  // namespace lantern
