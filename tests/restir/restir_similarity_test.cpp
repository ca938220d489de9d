// restir_surfaces_similar (shaders/shared/restir.h), the predicate restir.temporal and
// restir.spatial reuse a neighbour's reservoir by, compiled as C++: a case on each side of every
// threshold (relative view depth, both ways; shading normal; material; roughness) and the
// surfaces that must never match (sky, non-finite). Thresholds are those RestirIntegrator pushes
// for the default settings. Surfaces are built with restir_surface_pack and read through its
// accessors only, so the cases hold whatever the packed layout.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/constants.hpp>
#include <limits>

#include "lighting/frame/frame_inputs.h"
#include "lighting/restir/restir_integrator.h"
#include "lighting/restir/restir_settings.h"
#include "shared/restir.h"

namespace lantern::gpu {
namespace {

// A surface `depth` metres away with shading normal `n`.
RestirSurface surface(float depth, glm::vec3 n = glm::vec3(0.0f, 0.0f, 1.0f),
                      std::uint32_t material = 3, float roughness = 0.5f) {
  return restir_surface_pack(glm::vec4(1.0f, 2.0f, -depth, depth), n, n, glm::vec3(0.5f),
                             roughness, 0.0f, 0.5f, material);
}

// The similarity thresholds of the default settings, as the passes receive them.
glm::vec4 default_similarity() {
  lighting::FrameInputs inputs;
  inputs.width = 16;
  inputs.height = 16;
  return lighting::RestirIntegrator::make_push(lighting::make_restir_settings("balanced", {}),
                                               inputs)
      .similarity;
}

TEST(RestirSimilarity, DefaultThresholds) {
  const glm::vec4 t = default_similarity();
  EXPECT_FLOAT_EQ(t.x, 0.1f);   // relative depth
  EXPECT_FLOAT_EQ(t.y, 0.9f);   // cos between shading normals (25.8 degrees)
  EXPECT_FLOAT_EQ(t.z, 0.25f);  // roughness
}

TEST(RestirSimilarity, IdenticalSurfacesAreSimilar) {
  const glm::vec4 t = default_similarity();
  const RestirSurface s = surface(10.0f);
  EXPECT_TRUE(restir_surfaces_similar(s, restir_surface_depth(s), s, t));
}

// |expected - d_other| <= t * max(expected, d_other): a deeper neighbour at expected / (1 - k t)
// differs by exactly k t of its own depth, a nearer one at expected (1 - k t) by k t of expected.
TEST(RestirSimilarity, RelativeDepthBothWays) {
  const glm::vec4 t = default_similarity();
  const RestirSurface s = surface(10.0f);
  for (const float expected : {0.05f, 10.0f, 4000.0f}) {
    for (const float k : {0.95f, 1.05f}) {
      const bool similar = k < 1.0f;
      const RestirSurface deeper = surface(expected / (1.0f - k * t.x));
      const RestirSurface nearer = surface(expected * (1.0f - k * t.x));
      EXPECT_EQ(restir_surfaces_similar(s, expected, deeper, t), similar)
          << "expected depth " << expected << ", deeper by " << k << " x threshold";
      EXPECT_EQ(restir_surfaces_similar(s, expected, nearer, t), similar)
          << "expected depth " << expected << ", nearer by " << k << " x threshold";
    }
  }
}

// History is judged against the depth the previous camera saw this point at (expected_depth),
// not against this frame's depth.
TEST(RestirSimilarity, DepthIsComparedWithTheExpectedDepth) {
  const glm::vec4 t = default_similarity();
  const RestirSurface s = surface(10.0f);
  EXPECT_TRUE(restir_surfaces_similar(s, 20.0f, surface(20.0f), t));
  EXPECT_FALSE(restir_surfaces_similar(s, 20.0f, surface(10.0f), t));
  EXPECT_FALSE(restir_surfaces_similar(s, std::numeric_limits<float>::quiet_NaN(), s, t));
  EXPECT_FALSE(restir_surfaces_similar(s, 1e30f, s, t));
  // (An infinite expected depth passes: |Inf - d| <= t * Inf. Unreachable: restir.temporal
  // computes it as clip w of prev_view_proj x a finite position.)
}

// Normals acos(t.y) -+ 1 degree apart (quantisation of the packed normal is far below a degree).
TEST(RestirSimilarity, NormalAngle) {
  const glm::vec4 t = default_similarity();
  const float limit = std::acos(t.y);
  const float degree = glm::pi<float>() / 180.0f;
  const RestirSurface s = surface(10.0f);
  for (const float axis_angle : {0.0f, 1.3f, 2.9f}) {  // tilt towards different azimuths
    const glm::vec3 axis(std::cos(axis_angle), std::sin(axis_angle), 0.0f);
    for (const float angle : {limit - degree, limit + degree}) {
      const glm::vec3 n = std::cos(angle) * glm::vec3(0.0f, 0.0f, 1.0f) + std::sin(angle) * axis;
      EXPECT_EQ(restir_surfaces_similar(s, 10.0f, surface(10.0f, n), t), angle < limit)
          << "normals " << angle / degree << " degrees apart (limit " << limit / degree << ")";
    }
  }
  EXPECT_FALSE(restir_surfaces_similar(s, 10.0f, surface(10.0f, glm::vec3(0.0f, 0.0f, -1.0f)), t));
}

TEST(RestirSimilarity, Material) {
  const glm::vec4 t = default_similarity();
  const RestirSurface s = surface(10.0f, glm::vec3(0.0f, 0.0f, 1.0f), 3);
  EXPECT_TRUE(restir_surfaces_similar(s, 10.0f, surface(10.0f, glm::vec3(0.0f, 0.0f, 1.0f), 3), t));
  for (const std::uint32_t other : {0u, 2u, 4u, 1000u}) {
    EXPECT_FALSE(
        restir_surfaces_similar(s, 10.0f, surface(10.0f, glm::vec3(0.0f, 0.0f, 1.0f), other), t))
        << "material 3 against " << other;
  }
}

// Roughness t.z -+ 0.05 apart (quantisation of the packed roughness is below 0.005).
TEST(RestirSimilarity, Roughness) {
  const glm::vec4 t = default_similarity();
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  for (const float base : {0.0f, 0.3f, 0.7f}) {
    const RestirSurface s = surface(10.0f, n, 3, base);
    for (const float delta : {t.z - 0.05f, t.z + 0.05f}) {
      const float other = base + delta <= 1.0f ? base + delta : base - delta;
      EXPECT_EQ(restir_surfaces_similar(s, 10.0f, surface(10.0f, n, 3, other), t), delta < t.z)
          << "roughness " << base << " against " << other;
    }
  }
}

// No surface (sky: view depth 0) never matches, either way round, not even another sky pixel;
// non-finite positions pack to the sky surface.
TEST(RestirSimilarity, SkyAndNonFiniteNeverMatch) {
  const glm::vec4 t = default_similarity();
  const RestirSurface s = surface(10.0f);
  const RestirSurface sky = restir_surface_sky();
  EXPECT_FALSE(restir_surface_valid(sky));
  EXPECT_FALSE(restir_surfaces_similar(s, 10.0f, sky, t));
  EXPECT_FALSE(restir_surfaces_similar(sky, 0.0f, s, t));
  EXPECT_FALSE(restir_surfaces_similar(sky, 0.0f, sky, t));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (const glm::vec4 bad : {glm::vec4(nan, 0.0f, 0.0f, 10.0f), glm::vec4(0.0f, inf, 0.0f, 10.0f),
                              glm::vec4(0.0f, 0.0f, 0.0f, nan), glm::vec4(0.0f, 0.0f, 0.0f, -1.0f)}) {
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    const RestirSurface b = restir_surface_pack(bad, n, n, glm::vec3(0.5f), 0.5f, 0.0f, 0.5f, 3);
    EXPECT_FALSE(restir_surface_valid(b));
    EXPECT_FALSE(restir_surfaces_similar(s, 10.0f, b, t));
    EXPECT_FALSE(restir_surfaces_similar(b, 10.0f, s, t));
  }
}

}  // namespace
}  // namespace lantern::gpu
