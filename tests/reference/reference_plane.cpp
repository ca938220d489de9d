// The reference tests' plane scene, frames and assertions (reference_plane.h).
#include "tests/reference/reference_plane.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/level/primitives.h"
#include "lighting/integrators/offline_render.h"
#include "lighting/scene/frame_constants.h"

namespace lantern::test {

Level plane_level(float eye, float yfov) {
  Level level;
  level.name = "reference_plane";
  level.meshes.push_back(make_plane(glm::vec2(20.0f, 20.0f)));
  level.materials.push_back(make_lambert(kRho));
  Instance inst;
  inst.name = "plane";
  level.instances.push_back(inst);
  level.camera.position = glm::vec3(0.0f, eye, 0.0f);
  level.camera.orientation = look_at_orientation(level.camera.position, glm::vec3(0.0f));
  level.camera.yfov = yfov;
  level.has_camera = true;
  return level;
}

glm::dvec3 plane_point(const Camera& camera, std::uint32_t x, std::uint32_t y, glm::vec2 at) {
  const glm::mat4 inv = glm::inverse(lighting::camera_view_proj(camera, kSize, kSize));
  const glm::vec2 ndc = (glm::vec2(static_cast<float>(x), static_cast<float>(y)) + at) /
                            static_cast<float>(kSize) * 2.0f -
                        1.0f;
  const glm::vec4 a = inv * glm::vec4(ndc, 0.0f, 1.0f);
  const glm::vec4 b = inv * glm::vec4(ndc, 0.5f, 1.0f);
  const glm::dvec3 dir = glm::normalize(glm::dvec3(glm::vec3(b) / b.w - glm::vec3(a) / a.w));
  const glm::dvec3 origin = camera.position;
  return origin + dir * (-origin.y / dir.y);
}

Frames render_frames(runtime::Device& device, runtime::ShaderLibrary& shaders, const Level& level,
                     std::uint32_t frames, std::uint32_t spp) {
  lighting::OfflineRenderRequest request;
  request.integrator.name = "reference";
  request.integrator.spp = spp;
  request.width = kSize;
  request.height = kSize;
  request.frames = frames;
  request.animate = false;
  auto result = lighting::render_offline(device, shaders, level, request);
  EXPECT_EQ(result.images.size(), frames);
  for (const auto& image : result.images) EXPECT_EQ(image.count_non_finite(), 0u);
  return {std::move(result.images)};
}

void expect_matches(const Frames& frames, const PixelValue& expected, const PixelFilter& include) {
  const auto n = static_cast<double>(frames.images.size());
  double sum_mean = 0.0;
  double sum_expected = 0.0;
  double max_t = 0.0;
  int beyond = 0;
  int pixels = 0;
  for (std::uint32_t y = 0; y < kSize; ++y) {
    for (std::uint32_t x = 0; x < kSize; ++x) {
      if (include && !include(x, y)) continue;
      ++pixels;
      double s = 0.0;
      double s2 = 0.0;
      for (const auto& image : frames.images) {
        const double v = image.at(x, y)[0];
        s += v;
        s2 += v * v;
      }
      const double mean = s / n;
      const double var = std::max(s2 / n - mean * mean, 0.0) * n / (n - 1.0);
      const double se = std::sqrt(var / n);
      const double e = expected(x, y);
      sum_mean += mean;
      sum_expected += e;
      // A noiseless pixel (se ~ 0) must match to float precision.
      const double t = std::abs(mean - e) / std::max(se, 1e-4 * std::abs(e) + 1e-9);
      max_t = std::max(max_t, t);
      if (t > 3.3) ++beyond;
    }
  }
  std::printf(
      "reference vs closed form: %d pixels, mean ratio %.5f, max |t| %.2f, %d pixels beyond 3.3\n",
      pixels, sum_mean / sum_expected, max_t, beyond);
  ASSERT_GT(pixels, static_cast<int>(kSize * kSize / 4)) << "too few pixels compared";
  EXPECT_NEAR(sum_mean / sum_expected, 1.0, 0.005) << "image mean vs closed form";
  EXPECT_LT(max_t, 6.5) << "largest per-pixel |t|";
  EXPECT_LT(beyond, std::max(pixels / 100, 1)) << "pixels beyond |t| > 3.3";
}

}  // namespace lantern::test
