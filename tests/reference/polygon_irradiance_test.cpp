// Sanity of the closed form the reference tests rely on: Lambert's polygon irradiance formula
// (polygon_irradiance.h) against direct numerical integration of L cos cos / r^2 over the
// emitter's area, for a rectangle and a triangle in general position, and its limit pi L for a
// polygon covering the hemisphere.
#include "tests/reference/polygon_irradiance.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lantern {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Irradiance at x (normal n) from the parallelogram p0 + s e1 + t e2, s, t in [0,1] (or the
// triangle s + t <= 1), radiance L, by the midpoint rule on an n x n grid.
double numeric_irradiance(glm::dvec3 p0, glm::dvec3 e1, glm::dvec3 e2, bool triangle, glm::dvec3 x,
                          glm::dvec3 n, double radiance, int cells) {
  const glm::dvec3 normal = glm::normalize(glm::cross(e1, e2));
  const double area = glm::length(glm::cross(e1, e2));
  double sum = 0.0;
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      const double s = (i + 0.5) / cells;
      const double t = (j + 0.5) / cells;
      if (triangle && s + t > 1.0) continue;
      const glm::dvec3 p = p0 + s * e1 + t * e2;
      const glm::dvec3 d = p - x;
      const double r2 = glm::dot(d, d);
      const glm::dvec3 w = d / std::sqrt(r2);
      sum += std::max(glm::dot(n, w), 0.0) * std::abs(glm::dot(normal, w)) / r2;
    }
  }
  return radiance * sum * area / (cells * cells);
}

TEST(PolygonIrradiance, RectangleMatchesNumericIntegration) {
  const glm::dvec3 p0(-0.3, 1.2, -0.5);
  const glm::dvec3 e1(0.9, 0.1, 0.0);
  const glm::dvec3 e2(0.0, 0.2, 0.7);
  const glm::dvec3 x(0.4, 0.0, 0.3);
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.2, 1.0, -0.1));
  const double closed = test::polygon_irradiance({p0, p0 + e1, p0 + e1 + e2, p0 + e2}, x, n, 2.5);
  const double numeric = numeric_irradiance(p0, e1, e2, false, x, n, 2.5, 800);
  EXPECT_NEAR(closed, numeric, 1e-4 * numeric);
  // Winding does not matter (the formula returns the magnitude).
  EXPECT_NEAR(test::polygon_irradiance({p0 + e2, p0 + e1 + e2, p0 + e1, p0}, x, n, 2.5), closed,
              1e-12);
}

TEST(PolygonIrradiance, TriangleMatchesNumericIntegration) {
  const glm::dvec3 p0(0.1, 0.8, 0.2);
  const glm::dvec3 e1(1.0, 0.5, 0.0);
  const glm::dvec3 e2(-0.4, 0.3, 0.9);
  const glm::dvec3 x(0.0, 0.0, 0.0);
  const glm::dvec3 n(0.0, 1.0, 0.0);
  const double closed = test::polygon_irradiance({p0, p0 + e1, p0 + e2}, x, n, 1.0);
  const double numeric = numeric_irradiance(p0, e1, e2, true, x, n, 1.0, 1600);
  EXPECT_NEAR(closed, numeric, 1e-3 * numeric);
}

TEST(PolygonIrradiance, HugeSquareOverheadGivesPiL) {
  const double a = 1e5;
  const double e =
      test::polygon_irradiance({{-a, 1.0, -a}, {a, 1.0, -a}, {a, 1.0, a}, {-a, 1.0, a}},
                               glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0), 3.0);
  EXPECT_NEAR(e, kPiD * 3.0, 1e-3);
}

}  // namespace
}  // namespace lantern
