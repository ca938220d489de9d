// The one light evaluation every integrator calls (shaders/shared/light_eval.h), on the CPU
// against closed forms written out here: a Lambertian receiver (albedo rho, specular 0) under each
// light kind returns rho/pi x radiance x geometry, with KHR_lights_punctual's range window and
// cone; the solid-angle pdf of a triangle point; the ray origin helper; and the ReSTIR surface
// record keeping the material to unorm16 precision.
#include "shared/light_eval.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shared/bvh.h"
#include "shared/restir.h"

namespace lantern::gpu {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kRho = 0.5f;
const vec3 kUp(0.0f, 1.0f, 0.0f);

GpuLight point_light(vec3 position, vec3 radiance, float range) {
  GpuLight light{};
  light.p0 = vec4(position, uintBitsToFloat(kLightPoint));
  light.p2 = vec4(0.0f, 0.0f, 0.0f, range);
  light.radiance = vec4(radiance, 0.0f);
  return light;
}

// Contribution at the origin of a Lambertian plane facing +Y, seen from straight above.
vec3 lambert_contribution(GpuLight light, vec2 uv, vec3 x = vec3(0.0f)) {
  return light_eval_contribution(light, uv, x, kUp, kUp, kUp, vec3(kRho), 1.0f, 0.0f, 0.0f, 10.0f);
}

TEST(LightEval, PointLightIsInverseSquareTimesCosine) {
  // Light at (0.6, 0.8, 0): d = 1, cos = 0.8.
  const vec3 c = lambert_contribution(point_light(vec3(0.6f, 0.8f, 0.0f), vec3(2.0f), 0.0f),
                                      vec2(0.5f));
  EXPECT_NEAR(c.x, kRho / kPiD * 2.0 * 0.8, 1e-6);
}

TEST(LightEval, PointLightRangeAppliesTheWindow) {
  // d = 2 (light at (0, 2, 0)), range 3: window (1 - (2/3)^4)^2 = (65/81)^2.
  const double window = (65.0 / 81.0) * (65.0 / 81.0);
  const vec3 c = lambert_contribution(point_light(vec3(0.0f, 2.0f, 0.0f), vec3(1.0f), 3.0f),
                                      vec2(0.5f));
  EXPECT_NEAR(c.x, kRho / kPiD * 0.25 * window, 1e-7);
  // Beyond the range: nothing.
  const vec3 beyond = lambert_contribution(point_light(vec3(0.0f, 2.0f, 0.0f), vec3(1.0f), 1.9f),
                                           vec2(0.5f));
  EXPECT_EQ(beyond.x, 0.0f);
}

TEST(LightEval, SpotLightAppliesConeAndRange) {
  GpuLight light = point_light(vec3(0.0f, 2.0f, 0.0f), vec3(1.0f), 3.0f);
  light.p0.w = uintBitsToFloat(kLightSpot);
  const float cos_outer = std::cos(0.6f);
  const float cos_inner = std::cos(0.3f);
  light.p2 = vec4(cos_outer, cos_inner, 0.0f, 3.0f);
  // Axis tilted so the receiver sits 30% of the way (in cosine) from the outer cone.
  const float cos_theta = cos_outer + 0.3f * (cos_inner - cos_outer);
  const float sin_theta = std::sqrt(1.0f - cos_theta * cos_theta);
  light.p1 = vec4(sin_theta, -cos_theta, 0.0f, 0.0f);
  const double window = (65.0 / 81.0) * (65.0 / 81.0);
  const vec3 c = lambert_contribution(light, vec2(0.5f));
  EXPECT_NEAR(c.x, kRho / kPiD * 0.25 * window * 0.09, 1e-6);
  // Outside the cone: black.
  light.p1 = vec4(1.0f, 0.0f, 0.0f, 0.0f);
  EXPECT_EQ(lambert_contribution(light, vec2(0.5f)).x, 0.0f);
}

TEST(LightEval, DirectionalLightIsIrradianceTimesCosine) {
  GpuLight light{};
  light.p0 = vec4(0.0f, 0.0f, 0.0f, uintBitsToFloat(kLightDirectional));
  light.p1 = vec4(0.0f, -0.8f, 0.6f, 0.0f);  // travels down: cos = 0.8
  light.radiance = vec4(3.0f);
  const vec3 c = lambert_contribution(light, vec2(0.5f));
  EXPECT_NEAR(c.x, kRho / kPiD * 3.0 * 0.8, 1e-6);
  // The shadow ray ends kDirectionalShadowRadii scene radii towards the light.
  const vec3 y = light_eval_position(light, vec2(0.5f), vec3(0.0f), 10.0f);
  EXPECT_NEAR(length(y), kDirectionalShadowRadii * 10.0f, 1e-4f);
  EXPECT_NEAR(y.y, 0.8f * kDirectionalShadowRadii * 10.0f, 1e-4f);
}

TEST(LightEval, TriangleIsRadianceTimesCosLightOverDistanceSquaredAndItsPdf) {
  // A triangle facing down at height 2; uv = (0, *) lands on vertex 0 (barycentrics (1, 0, 0)).
  GpuLight light{};
  const vec3 v0(0.0f, 2.0f, 0.0f);
  light.p0 = vec4(v0, uintBitsToFloat(kLightTriangle));
  light.p1 = vec4(1.0f, 0.0f, 0.0f, 0.0f);  // v1 - v0
  light.p2 = vec4(0.0f, 0.0f, 1.0f, 0.0f);  // v2 - v0: front normal p1 x p2 = -Y
  light.radiance = vec4(4.0f);
  const vec3 y = light_eval_position(light, vec2(0.0f, 0.5f), vec3(0.0f), 10.0f);
  EXPECT_NEAR(length(y - v0), 0.0f, 1e-6f);
  const vec3 c = lambert_contribution(light, vec2(0.0f, 0.5f), vec3(0.0f));
  // cos at the receiver 1, at the light 1, d^2 = 4.
  EXPECT_NEAR(c.x, kRho / kPiD * 4.0 / 4.0, 1e-6);
  EXPECT_FLOAT_EQ(light_eval_point_pdf(light), 2.0f);  // 1 / area (0.5 m^2)
  // Solid-angle density: (1 / area) d^2 / cos_light = 2 * 4 / 1.
  EXPECT_NEAR(light_eval_solid_angle_pdf(light, kUp, 4.0f), 8.0f, 1e-5f);
  // Seen from above (behind the one-sided triangle): no light, no density.
  const vec3 above(0.0f, 4.0f, 0.0f);
  EXPECT_EQ(light_eval_contribution(light, vec2(0.0f, 0.5f), above, -kUp, -kUp, -kUp, vec3(kRho),
                                    1.0f, 0.0f, 0.0f, 10.0f).x,
            0.0f);
  EXPECT_EQ(light_eval_solid_angle_pdf(light, -kUp, 4.0f), 0.0f);
}

TEST(LightEval, BelowTheGeometricNormalIsBlack) {
  const vec3 c = lambert_contribution(point_light(vec3(0.0f, -1.0f, 0.0f), vec3(1.0f), 0.0f),
                                      vec2(0.5f));
  EXPECT_EQ(c.x, 0.0f);
}

TEST(LightEval, RayOriginLeavesTheSurfaceByThePositionEpsilon) {
  const vec3 p(1e5f, 3.0f, -2.0f);
  const vec3 o = bvh_ray_origin(p, kUp);
  EXPECT_EQ(o.x, p.x);
  EXPECT_FLOAT_EQ(o.y - p.y, bvh_position_epsilon(1e5f));
  EXPECT_FLOAT_EQ(bvh_ray_origin(vec3(0.0f), kUp).y, kBvhShadowEpsilon);
}

// The ReSTIR surface record keeps the material within unorm16 rounding (half a step: 7.6e-6), so
// a single light over a grey plane shades as the baseline does (unorm8 read 0.5 as 128/255).
TEST(LightEval, RestirSurfaceKeepsMaterialToUnorm16) {
  const float step = 0.5f / 65535.0f;
  for (const float a : {0.5f, 0.05f, 0.3f, 0.999f, 0.0f, 1.0f}) {
    const RestirSurface s = restir_surface_pack(vec4(1.0f, 2.0f, 3.0f, 4.0f), kUp, kUp,
                                                vec3(a, 0.25f * a, 1.0f - a), a, 1.0f - a,
                                                0.5f * a, 70000u);
    const vec3 albedo = restir_surface_albedo(s);
    EXPECT_NEAR(albedo.x, a, step);
    EXPECT_NEAR(albedo.y, 0.25f * a, step);
    EXPECT_NEAR(albedo.z, 1.0f - a, step);
    EXPECT_NEAR(restir_surface_roughness(s), a, step);
    EXPECT_NEAR(restir_surface_metallic(s), 1.0f - a, step);
    EXPECT_NEAR(restir_surface_specular(s), 0.5f * a, step);
    EXPECT_EQ(restir_surface_material(s), 70000u) << "material ids above 16 bits survive";
  }
}

}  // namespace
}  // namespace lantern::gpu
