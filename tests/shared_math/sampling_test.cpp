// Light sampling geometry: uniform triangle sampling with its solid-angle pdf reproduces the
// analytic solid angle (Van Oosterom-Strackee), and punctual falloffs follow KHR_lights_punctual.
#include "shared/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>

#include "shared/rng.h"
#include "statistics.h"

namespace lantern::gpu {
namespace {

// Solid angle of triangle (a, b, c) seen from the origin (Van Oosterom & Strackee 1983).
double solid_angle(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  double numerator = std::abs(glm::dot(a, glm::cross(b, c)));
  double denominator =
      la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  return 2.0 * std::atan2(numerator, denominator);
}

TEST(Sampling, TriangleSolidAnglePdfMatchesVanOosteromStrackee) {
  struct Case {
    vec3 p0, p1, p2, x;
  };
  const Case cases[] = {
      {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {0, 0, 0}},              // small, in front
      {{-2, -1, 0.5f}, {3, -1, 0.4f}, {0, 4, 0.6f}, {0, 0, 0}},  // large and close: wide angle
      {{5, 5, 5}, {5.2f, 5, 5}, {5, 5.3f, 5.1f}, {1, 2, 0}},     // far and tilted
      {{0, 0, 1}, {0, 1, 1}, {1, 0, 1}, {0.2f, 0.2f, 0}},        // opposite winding
  };
  uint rng = rng_init(uvec2(7u), 0u, 47u, 0u);
  for (const Case& c : cases) {
    vec3 normal = normalize(cross(c.p1 - c.p0, c.p2 - c.p0));
    float area = triangle_area(c.p0, c.p1, c.p2);
    test::RunningStats omega;
    for (int i = 0; i < 200000; ++i) {
      vec3 p = triangle_point(c.p0, c.p1, c.p2, triangle_sample_barycentrics(rng_next_vec2(rng)));
      vec3 to_receiver = c.x - p;
      float dist2 = dot(to_receiver, to_receiver);
      // Geometric solid angle (two-sided): the cosine at the light taken in absolute value.
      float cos_light = std::abs(dot(normal, to_receiver)) / std::sqrt(dist2);
      float pdf = triangle_solid_angle_pdf(area, dist2, cos_light);
      ASSERT_GT(pdf, 0.0f);
      omega.add(1.0 / double(pdf));
    }
    double expected =
        solid_angle(glm::dvec3(c.p0 - c.x), glm::dvec3(c.p1 - c.x), glm::dvec3(c.p2 - c.x));
    std::printf("triangle solid angle: MC %.6f +- %.6f, analytic %.6f\n", omega.mean(),
                omega.standard_error(), expected);
    EXPECT_NEAR(omega.mean(), expected, 3.0 * omega.standard_error() + 1e-5 * expected);
  }
}

TEST(Sampling, TriangleBarycentricsAreUniform) {
  // Uniform on the triangle <=> b0 has density 2(1 - b0) and b1/(b1 + b2) is uniform.
  uint rng = rng_init(uvec2(8u), 0u, 48u, 0u);
  constexpr int kBins = 20;
  std::vector<std::uint64_t> b0_counts(kBins, 0), ratio_counts(kBins, 0);
  for (int i = 0; i < 500000; ++i) {
    vec3 bary = triangle_sample_barycentrics(rng_next_vec2(rng));
    ASSERT_GE(min(bary.x, min(bary.y, bary.z)), -1e-6f);
    ASSERT_NEAR(bary.x + bary.y + bary.z, 1.0f, 1e-6f);
    b0_counts[min(int(bary.x * kBins), kBins - 1)]++;
    float rest = bary.y + bary.z;
    if (rest > 0.0f) ratio_counts[min(int(bary.y / rest * kBins), kBins - 1)]++;
  }
  std::vector<double> b0_p, ratio_p(kBins, 1.0 / kBins);
  for (int i = 0; i < kBins; ++i) {
    double lo = double(i) / kBins, hi = double(i + 1) / kBins;
    b0_p.push_back((1.0 - lo) * (1.0 - lo) - (1.0 - hi) * (1.0 - hi));  // ∫ 2(1-b) db
  }
  int dof = 0;
  double chi2_b0 = test::chi_square(b0_counts, b0_p, dof);
  EXPECT_LT(chi2_b0, test::chi_square_critical(dof, test::kZ1e3));
  double chi2_ratio = test::chi_square(ratio_counts, ratio_p, dof);
  EXPECT_LT(chi2_ratio, test::chi_square_critical(dof, test::kZ1e3));
}

TEST(Sampling, AreaToSolidAngleRejectsBackFacing) {
  EXPECT_EQ(area_to_solid_angle_pdf(1.0f, 4.0f, 0.0f), 0.0f);
  EXPECT_EQ(area_to_solid_angle_pdf(1.0f, 4.0f, -0.5f), 0.0f);
  EXPECT_FLOAT_EQ(area_to_solid_angle_pdf(0.5f, 4.0f, 0.5f), 4.0f);
}

TEST(Sampling, SpotConeFollowsKhrLightsPunctual) {
  const float cos_outer = std::cos(0.6f);
  const float cos_inner = std::cos(0.3f);
  EXPECT_EQ(spot_cone_falloff(1.0f, cos_outer, cos_inner), 1.0f);
  EXPECT_EQ(spot_cone_falloff(cos_inner, cos_outer, cos_inner), 1.0f);
  EXPECT_EQ(spot_cone_falloff(cos_outer, cos_outer, cos_inner), 0.0f);
  EXPECT_EQ(spot_cone_falloff(-1.0f, cos_outer, cos_inner), 0.0f);
  // Halfway in cosine: the spec's linear ramp squared.
  EXPECT_NEAR(spot_cone_falloff(0.5f * (cos_outer + cos_inner), cos_outer, cos_inner), 0.25f,
              1e-5f);
  // 30% of the way in cosine from the outer cone: 0.3^2.
  EXPECT_NEAR(spot_cone_falloff(cos_outer + 0.3f * (cos_inner - cos_outer), cos_outer, cos_inner),
              0.09f, 1e-5f);
  // Monotonic between the cones.
  float previous = 0.0f;
  for (int i = 0; i <= 100; ++i) {
    float c = cos_outer + (cos_inner - cos_outer) * float(i) / 100.0f;
    float a = spot_cone_falloff(c, cos_outer, cos_inner);
    EXPECT_GE(a, previous);
    previous = a;
  }
  // Inner == outer: the spec's 0.001 floor keeps it finite (a hard edge).
  EXPECT_TRUE(std::isfinite(spot_cone_falloff(0.9f, 0.9f, 0.9f)));
}

TEST(Sampling, PunctualDistanceFalloff) {
  EXPECT_FLOAT_EQ(punctual_distance_falloff(4.0f, 0.0f), 0.25f);  // no range: inverse square
  EXPECT_EQ(punctual_distance_falloff(9.0f, 3.0f), 0.0f);         // at the range: zero
  EXPECT_EQ(punctual_distance_falloff(16.0f, 3.0f), 0.0f);
  // d = 2, range 3: 1/d^2 (1 - (2/3)^4)^2 = 0.25 * (65/81)^2 = 0.160989...
  EXPECT_NEAR(punctual_distance_falloff(4.0f, 3.0f), 0.25 * (65.0 / 81.0) * (65.0 / 81.0), 1e-7);
  // d = 0.5, range 1: 4 * (1 - 1/16)^2 = 3.515625
  EXPECT_NEAR(punctual_distance_falloff(0.25f, 1.0f), 3.515625, 1e-6);
  EXPECT_EQ(punctual_distance_falloff(0.0f, 0.0f), 0.0f);  // degenerate: no Inf
}

TEST(Sampling, DirectionalLightPointsAgainstTravel) {
  vec3 to_light = directional_light_to_light(vec3(0.0f, -2.0f, 0.0f));
  EXPECT_FLOAT_EQ(to_light.y, 1.0f);
  EXPECT_FLOAT_EQ(length(to_light), 1.0f);
}

}  // namespace
}  // namespace lantern::gpu
