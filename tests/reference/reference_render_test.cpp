// integrators.reference on the GPU (render_offline, as `lantern render --integrator reference`
// runs it) against closed forms, on a Lambertian plane (y = 0, albedo rho, specular 0):
//   (a) under a point light: rho/pi * I cos / d^2 (light sampling of a delta light is exact, so
//       per pixel within 0.1% and the image mean within 0.5%);
//   (b) under an emissive rectangle facing down: rho/pi * Lambert's polygon irradiance;
//   (d) under a constant environment map of radiance L: rho * L; under a non-constant map:
//       rho/pi * E, E = the map's cosine-weighted integral over the upper hemisphere by CPU
//       quadrature (the same everywhere on the unoccluded plane).
// The scene, the frames and the assertions (per-pixel t against the closed form, the image mean
// within 0.5%, no NaN/Inf) are tests/reference/reference_plane.h's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <memory>

#include "engine/level/primitives.h"
#include "lighting/lights/environment_map.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/image/image_io.h"
#include "shared/environment.h"
#include "tests/reference/polygon_irradiance.h"
#include "tests/reference/reference_plane.h"
#include "tests/runtime/gpu_test_support.h"
#include "tests/runtime/scratch_dir.h"

namespace lantern {
namespace {

using test::expect_matches;
using test::Frames;
using test::kPiD;
using test::kRho;
using test::plane_level;
using test::plane_point;
using test::render_frames;

class ReferenceRenderTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;
};

TEST_F(ReferenceRenderTest, PlaneUnderPointLightMatchesClosedForm) {
  Level level = plane_level(4.0f, 0.6f);
  Light light;
  light.type = LightType::Point;
  light.color = glm::vec3(2.0f);
  light.position = glm::vec3(0.4f, 1.5f, -0.3f);
  level.lights.push_back(light);
  const Frames frames = render_frames(device, shaders, level, 2, 4);
  const glm::dvec3 p(light.position);
  expect_matches(frames, [&](std::uint32_t x, std::uint32_t y) {
    const glm::dvec3 q = plane_point(level.camera, x, y);
    const glm::dvec3 d = p - q;
    const double d2 = glm::dot(d, d);
    return kRho / kPiD * 2.0 * (d.y / std::sqrt(d2)) / d2;
  });
}

TEST_F(ReferenceRenderTest, PlaneUnderEmissiveRectangleMatchesPolygonFormula) {
  Level level = plane_level(0.9f, 1.2f);
  // A 1.0 x 0.6 rectangle at height 1.2 facing down (-Y), radiance 5.
  const glm::vec3 centre(0.3f, 1.2f, 0.1f);
  const glm::vec3 half(0.5f, 0.0f, 0.3f);
  Mesh quad;
  quad.name = "light";
  quad.positions = {centre + glm::vec3(-half.x, 0, -half.z), centre + glm::vec3(half.x, 0, -half.z),
                    centre + glm::vec3(half.x, 0, half.z), centre + glm::vec3(-half.x, 0, half.z)};
  quad.normals.assign(4, glm::vec3(0.0f, -1.0f, 0.0f));
  // Counter-clockwise seen from below: front face (cross(e1, e2)) points down.
  quad.indices = {0, 1, 2, 0, 2, 3};
  const glm::vec3 n =
      glm::cross(quad.positions[1] - quad.positions[0], quad.positions[2] - quad.positions[0]);
  ASSERT_LT(n.y, 0.0f) << "the rectangle must face the plane";
  quad.bounds.min = centre - half;
  quad.bounds.max = centre + half;
  level.meshes.push_back(quad);
  Material emitter = make_lambert(0.0f);
  emitter.emissive_factor = glm::vec3(5.0f);
  level.materials.push_back(emitter);
  Instance inst;
  inst.name = "light";
  inst.mesh = 1;
  inst.material = 1;
  level.instances.push_back(inst);

  const Frames frames = render_frames(device, shaders, level, 32, 32);
  std::vector<glm::dvec3> polygon;
  for (const glm::vec3& v : quad.positions) polygon.emplace_back(v);
  expect_matches(frames, [&](std::uint32_t x, std::uint32_t y) {
    const glm::dvec3 q = plane_point(level.camera, x, y);
    return kRho / kPiD * test::polygon_irradiance(polygon, q, glm::dvec3(0, 1, 0), 5.0);
  });
}

// Writes a W x H environment map `radiance(x, y)` to a temporary EXR and names it in the level.
template <class F>
void add_environment(Level& level, const std::string& file, std::uint32_t w, std::uint32_t h,
                     F radiance, const glm::quat& rotation) {
  runtime::ImageRGBA32F image(w, h);
  for (std::uint32_t y = 0; y < h; ++y) {
    for (std::uint32_t x = 0; x < w; ++x) {
      float* p = image.at(x, y);
      p[0] = p[1] = p[2] = radiance(x, y);
      p[3] = 1.0f;
    }
  }
  const std::filesystem::path path = test::process_scratch_dir() / file;
  runtime::write_image(path, image);
  level.environment = EnvironmentMap{path, 1.0f, rotation};
}

TEST_F(ReferenceRenderTest, PlaneUnderConstantEnvironmentGetsRhoL) {
  Level level = plane_level(4.0f, 0.6f);
  add_environment(
      level, "constant.exr", 8, 4, [](auto, auto) { return 1.5f; },
      glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
  const Frames frames = render_frames(device, shaders, level, 32, 16);
  expect_matches(frames, [](std::uint32_t, std::uint32_t) { return kRho * 1.5; });
}

TEST_F(ReferenceRenderTest, PlaneUnderVaryingEnvironmentMatchesQuadrature) {
  Level level = plane_level(4.0f, 0.6f);
  const glm::quat rotation = glm::quat(glm::radians(glm::vec3(25.0f, 40.0f, 0.0f)));
  add_environment(
      level, "varying.exr", 32, 16,
      [](std::uint32_t x, std::uint32_t y) {
        return 0.05f + static_cast<float>((x * 5 + y * 3) % 7) + (x == 9 && y == 4 ? 400.0f : 0.0f);
      },
      rotation);
  // E = integral over the upper hemisphere of L(w) cos(theta), midpoint rule uniform in (phi,
  // cos theta) (equal solid angle per cell), L from the map's own lookup (tested on the CPU).
  const lighting::EnvironmentDistribution env =
      lighting::EnvironmentDistribution::load(*level.environment);
  const int n = 2048;
  double irradiance = 0.0;
  for (int i = 0; i < n; ++i) {
    const double z = (i + 0.5) / n;  // cos theta from +Y
    const double r = std::sqrt(1.0 - z * z);
    for (int j = 0; j < n; ++j) {
      const double phi = 2.0 * kPiD * (j + 0.5) / n;
      const glm::vec3 dir(static_cast<float>(r * std::cos(phi)), static_cast<float>(z),
                          static_cast<float>(r * std::sin(phi)));
      irradiance += gpu::env_radiance(env.view(), env.header(), dir).x * z;
    }
  }
  irradiance *= 2.0 * kPiD / (static_cast<double>(n) * n);
  const Frames frames = render_frames(device, shaders, level, 32, 32);
  expect_matches(frames, [&](std::uint32_t, std::uint32_t) { return kRho / kPiD * irradiance; });
}

}  // namespace
}  // namespace lantern
