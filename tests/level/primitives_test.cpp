// Procedural primitives: closed spheres and boxes face outwards, counts follow the parameters,
// quad-grid radiances follow their pattern.
#include "engine/level/primitives.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

namespace lantern {
namespace {

// Sum over triangles of signed volume: positive and equal to the solid's volume when every
// triangle faces outwards.
float signed_volume(const Mesh& m) {
  float v = 0.0f;
  for (std::size_t t = 0; t < m.indices.size(); t += 3)
    v += glm::dot(m.positions[m.indices[t]],
                  glm::cross(m.positions[m.indices[t + 1]], m.positions[m.indices[t + 2]])) /
         6.0f;
  return v;
}

TEST(Primitives, ClosedMeshesFaceOutwards) {
  EXPECT_NEAR(signed_volume(make_box({1, 2, 3})), 6.0f, 1e-4f);
  EXPECT_NEAR(signed_volume(make_box({1, 2, 3}, true)), -6.0f, 1e-4f);
  const float sphere = 4.0f / 3.0f * glm::pi<float>();
  EXPECT_NEAR(signed_volume(make_ico_sphere(1.0f, 4)), sphere, 0.02f * sphere);
  EXPECT_NEAR(signed_volume(make_uv_sphere(1.0f, 64, 32)), sphere, 0.02f * sphere);
  EXPECT_EQ(make_ico_sphere(1.0f, 2).triangle_count(), 320u);
}

TEST(Primitives, QuadGridRadiancePatterns) {
  EmissiveQuadGrid g;
  g.nx = 5;
  g.ny = 2;
  g.radiance_min = 1.0f;
  g.radiance_max = 1e4f;
  g.pattern = "log";
  EXPECT_NEAR(quad_grid_radiance(g, 0), 1.0f, 1e-5f);
  EXPECT_NEAR(quad_grid_radiance(g, 9), 1e4f, 1.0f);
  EXPECT_NEAR(quad_grid_radiance(g, 3) / quad_grid_radiance(g, 2),
              quad_grid_radiance(g, 2) / quad_grid_radiance(g, 1), 1e-3f);
  g.pattern = "checker";
  EXPECT_EQ(quad_grid_radiance(g, 0), 1.0f);
  EXPECT_EQ(quad_grid_radiance(g, 1), 1e4f);
  EXPECT_EQ(quad_grid_radiance(g, 5), 1e4f);  // next row starts shifted
  g.levels = 3;
  g.pattern = "log";
  const auto bins = make_emissive_quad_grid(g);
  ASSERT_EQ(bins.size(), 3u);
  std::size_t tris = 0;
  for (const auto& b : bins) tris += b.mesh.triangle_count();
  EXPECT_EQ(tris, 20u);
  EXPECT_NEAR(bins[1].radiance, 100.0f, 0.01f);  // log-spaced bin centres: 1, 100, 10^4
}

}  // namespace
}  // namespace lantern
