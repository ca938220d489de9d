// vulkan_perspective: Vulkan clip conventions (y down, depth 0 at near and 1 at far or infinity).
#include "engine/world/projection.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>

namespace lantern {
namespace {

glm::vec3 ndc(const glm::mat4& p, const glm::vec3& view) {
  const glm::vec4 c = p * glm::vec4(view, 1.0f);
  EXPECT_GT(c.w, 0.0f);
  return glm::vec3(c) / c.w;
}

TEST(Projection, DepthZeroAtNearOneAtFar) {
  const glm::mat4 p = vulkan_perspective(0.8f, 1.5f, 0.1f, 50.0f);
  EXPECT_NEAR(ndc(p, {0, 0, -0.1f}).z, 0.0f, 1e-6f);
  EXPECT_NEAR(ndc(p, {0, 0, -50.0f}).z, 1.0f, 1e-6f);
  const float mid = ndc(p, {0, 0, -3.0f}).z;
  EXPECT_GT(mid, 0.0f);
  EXPECT_LT(mid, 1.0f);
}

TEST(Projection, InfiniteFarApproachesOne) {
  const glm::mat4 p = vulkan_perspective(0.8f, 1.5f, 0.1f, 0.0f);
  EXPECT_NEAR(ndc(p, {0, 0, -0.1f}).z, 0.0f, 1e-6f);
  EXPECT_NEAR(ndc(p, {0, 0, -1e6f}).z, 1.0f, 1e-6f);
  EXPECT_LT(ndc(p, {0, 0, -1e6f}).z, 1.0f + 1e-7f);
}

TEST(Projection, YPointsDownAndFovMapsToTheEdges) {
  const float yfov = 0.9f, aspect = 2.0f;
  const glm::mat4 p = vulkan_perspective(yfov, aspect, 0.05f, 10.0f);
  const float d = 4.0f, half = d * std::tan(0.5f * yfov);
  // The top edge of the view frustum is NDC y = -1 (top row of the image), the right edge x = +1.
  EXPECT_NEAR(ndc(p, {0, half, -d}).y, -1.0f, 1e-5f);
  EXPECT_NEAR(ndc(p, {0, -half, -d}).y, 1.0f, 1e-5f);
  EXPECT_NEAR(ndc(p, {half * aspect, 0, -d}).x, 1.0f, 1e-5f);
}

}  // namespace
}  // namespace lantern
