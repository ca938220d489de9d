// Closed forms for the reference tests: irradiance from a uniformly emitting (Lambertian,
// radiance L) planar polygon at a receiver point, by Lambert's polygon formula (Lambert 1760;
// Arvo 1995, "Applications of irradiance tensors"):
//   E(x, n) = L / 2 * sum_i theta_i * (n . g_i),
//   g_i = unit(u_i x u_{i+1}), u_i = unit(v_i - x), theta_i = acos(u_i . u_{i+1}),
// the sum running over the polygon's edges. The sign of the sum depends on the winding as seen
// from x: counter-clockwise seen from x (looking at the polygon) gives a negative sum, so the
// formula returns the magnitude. Valid when the whole polygon lies above the receiver's tangent
// plane (the tests place it so; no horizon clipping here).
#pragma once

#include <cmath>
#include <glm/glm.hpp>
#include <vector>

namespace lantern::test {

inline double polygon_irradiance(const std::vector<glm::dvec3>& vertices, glm::dvec3 x,
                                 glm::dvec3 n, double radiance) {
  double sum = 0.0;
  const std::size_t count = vertices.size();
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec3 a = glm::normalize(vertices[i] - x);
    const glm::dvec3 b = glm::normalize(vertices[(i + 1) % count] - x);
    const double theta = std::acos(glm::clamp(glm::dot(a, b), -1.0, 1.0));
    const glm::dvec3 c = glm::cross(a, b);
    const double len = glm::length(c);
    if (len <= 0.0) continue;
    sum += theta * glm::dot(n, c / len);
  }
  return std::abs(0.5 * radiance * sum);
}

}  // namespace lantern::test
