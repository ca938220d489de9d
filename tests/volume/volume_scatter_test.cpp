// Single scattering on the GPU against closed forms (issue 14), for every integrator. Each pixel
// of the foggy level must equal the fog-free render (the renderer's own: it isolates the media)
// times the transmittance of the surface's camera and light legs, plus the in-scattered light
// along its camera ray:
// - Sun over a slab: a floor inside a homogeneous fog slab (generated constant box, top at
//   kSlabTop) under a directional light, the camera inside the slab looking down. With mu the
//   sun's elevation sine and d the ray (d.y < 0) from height z0 to the floor at distance D:
//     L = L_clear e^{-s_t D} e^{-s_t H / mu}
//       + s_s phase(d.l) E e^{-s_t (H - z0) / mu} (1 - e^{-k D}) / k,  k = s_t (1 - d.y / mu).
// - A point light in a thin fog (the box reaches 5 m beyond every path: homogeneous throughout):
//     L = L_clear e^{-s_t (D + |p - light|)}
//       + integral over the ray of s_s phase I / r^2 e^{-s_t (t + r)} dt,
//   integrated in the angle the ray subtends at the light (t = delta + h tan(theta), so
//   dt / r^2 = dtheta / h: a smooth integrand) by Simpson's rule.
// Tolerances: the image mean within 0.5% for the reference, 1% for baseline and ReSTIR (64
// frames, static camera); the mean absolute per-pixel error is printed and bounded loosely (5%
// for the reference, 10% for the others: the estimators are noisy per pixel by design, most of
// all the sun's transmittance through the slab's top cell, which ratio tracking estimates).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <glm/glm.hpp>
#include <string>

#include "runtime/gpu/shader_library.h"
#include "runtime/image/image_io.h"
#include "shared/volume.h"
#include "tests/restir/restir_test_support.h"
#include "tests/runtime/gpu_test_support.h"
#include "tests/runtime/scratch_dir.h"
#include "tests/volume/volume_render_support.h"

namespace lantern {
namespace {

constexpr std::uint32_t kWidth = 64;
constexpr std::uint32_t kHeight = 36;

double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += f(a + i * h) * (i % 2 ? 4.0 : 2.0);
  return sum * h / 3.0;
}

std::string grey(double v) {
  const std::string s = std::to_string(v);
  return "[" + s + ", " + s + ", " + s + "]";
}

struct Fog {
  double scattering = 0.0;
  double absorption = 0.0;
  double anisotropy = 0.0;
  double extinction() const { return scattering + absorption; }
  // The level's volume entry: a constant box of `size` (x z centred, y from 0) moved by `lift`.
  // `extra`: more keys of the entry (", \"behaviour\": ..."), or empty.
  std::string entry(const std::string& size, double voxel, double lift,
                    const std::string& extra = "") const {
    return R"({ "name": "fog", "generate": { "type": "constant", "size": )" + size +
           R"(, "voxel_size": )" + std::to_string(voxel) + R"( }, "translation": [0, )" +
           std::to_string(lift) + R"(, 0], "scattering": )" + grey(scattering) +
           R"(, "absorption": )" + grey(absorption) + R"(, "anisotropy": )" +
           std::to_string(anisotropy) + extra + " }";
  }
};

// Which integrators a closed form checks, and how long the reference accumulates.
struct Checks {
  bool animate = false;  // step the level (the camera's path, the media's behaviours)
  bool reference_only = false;
  std::uint32_t reference_spp = 64;
};

class VolumeScatterTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;

  // For each integrator: renders the clear and the foggy level and compares every pixel's
  // green channel with expected(pixel, clear value).
  void expect_matches(const Level& clear, const Level& foggy,
                      const std::function<double(std::uint32_t, std::uint32_t, double)>& expected,
                      const char* what, Checks checks = {}) {
    const bool animate = checks.animate;
    for (const char* integrator : {"reference", "baseline", "restir"}) {
      const bool reference = std::string(integrator) == "reference";
      if (checks.reference_only && !reference) continue;
      const test::VolumeRender r{.width = kWidth,
                                 .height = kHeight,
                                 .frames = reference ? 4u : 64u,
                                 .spp = checks.reference_spp,
                                 .seed = 5,
                                 .animate = animate};
      const runtime::ImageRGBA32F a = test::render_volume_level(device, shaders, clear, integrator, r);
      const runtime::ImageRGBA32F b = test::render_volume_level(device, shaders, foggy, integrator, r);
      double sum_rendered = 0.0, sum_expected = 0.0, abs_error = 0.0;
      for (std::uint32_t y = 0; y < kHeight; ++y)
        for (std::uint32_t x = 0; x < kWidth; ++x) {
          const std::size_t i = 4 * (std::size_t{y} * kWidth + x) + 1;
          const double e = expected(x, y, a.pixels[i]);
          ASSERT_GT(e, 0.0) << what << ": pixel " << x << "," << y;
          sum_rendered += b.pixels[i];
          sum_expected += e;
          abs_error += std::abs(b.pixels[i] / e - 1.0);
        }
      const double ratio = sum_rendered / sum_expected;
      const double mean_abs = abs_error / (double(kWidth) * kHeight);
      std::printf("[volume] %s, %s: image mean / closed form %.5f, mean |pixel error| %.4f\n",
                  what, integrator, ratio, mean_abs);
      EXPECT_NEAR(ratio, 1.0, reference ? 0.005 : 0.01) << what << ", " << integrator;
      EXPECT_LT(mean_abs, reference ? 0.05 : 0.1) << what << ", " << integrator;
    }
  }

  void expect_sun_over_a_slab(const std::string& camera, const std::string& paths,
                              const std::string& slab_behaviour, bool animate, const char* what);
};

// The sun over a slab: `camera` is the level's camera entry (and `paths` its paths, or empty),
// `slab_behaviour` more keys of the slab's entry (a behaviour) or empty; with `animate` the
// frames step the level: the camera's path must keep the pixels' ray directions and the
// camera's height, the slab's motion must keep it covering the camera's view (then every frame
// has the same closed form).
void VolumeScatterTest::expect_sun_over_a_slab(const std::string& camera,
                                               const std::string& paths,
                                               const std::string& slab_behaviour, bool animate,
                                               const char* what) {
  const Fog fog{.scattering = 0.2, .absorption = 0.1, .anisotropy = 0.3};
  const double top = 2.0;  // slab y in [-1, 2]: the floor and the camera inside it
  const double irradiance = 3.0;
  const glm::dvec3 travel = glm::normalize(glm::dvec3(0.5, -1.0, 0.3));
  const glm::dvec3 to_sun = -travel;
  const double mu = to_sun.y;
  auto level_json = [&](const std::string& volume) {
    std::string json = R"({
  "materials": { "floor": { "base_color": [0.6, 0.6, 0.6], "roughness": 1.0 } },
  "primitives": [ { "type": "plane", "size": [40, 40], "material": "floor" } ],
  "lights": [ { "type": "directional", "direction": [0.5, -1.0, 0.3], "color": [1, 1, 1], "intensity": )" +
                       std::to_string(irradiance) + R"( } ],)" + paths + R"(
  "camera": )" + camera + " }";
    return test::with_volume(json, volume);
  };
  const auto clear = test::level_from_json("slab_clear", level_json(""));
  const auto foggy =
      test::level_from_json("slab_fog", level_json(fog.entry("[30, 3, 30]", 0.25, -1.0,
                                                             slab_behaviour)));
  const double s_t = fog.extinction();
  expect_matches(
      *clear, *foggy,
      [&](std::uint32_t x, std::uint32_t y, double clear_value) {
        const test::PixelRay ray = test::pixel_ray(*clear, kWidth, kHeight, x, y);
        EXPECT_LT(ray.dir.y, 0.0);
        const double z0 = ray.origin.y;
        const double distance = -z0 / ray.dir.y;
        const double floor = clear_value * std::exp(-s_t * distance) * std::exp(-s_t * top / mu);
        const double k = s_t * (1.0 - ray.dir.y / mu);
        const double phase = gpu::hg_phase(float(glm::dot(ray.dir, to_sun)), float(fog.anisotropy));
        const double inscattered = fog.scattering * phase * irradiance *
                                   std::exp(-s_t * (top - z0) / mu) *
                                   (1.0 - std::exp(-k * distance)) / k;
        return floor + inscattered;
      },
      what, {.animate = animate});
}

TEST_F(VolumeScatterTest, DirectionalLightOverAHomogeneousSlabSeenFromInside) {
  expect_sun_over_a_slab(
      R"({ "position": [0.0, 1.5, 0.0], "target": [0.0, 0.0, -1.5], "yfov_deg": 40 })", "", "",
      false, "sun over a slab");
}

// The same slab with the camera sliding 3 m sideways over the 64 frames (4.7 cm a frame at
// 60 Hz): the media history is reprojected and shifted along the moving rays every frame
// (volume_temporal_shift), and the mean must still be the closed form's.
TEST_F(VolumeScatterTest, DirectionalLightOverASlabWithTheCameraSliding) {
  expect_sun_over_a_slab(
      R"({ "position": [-1.5, 1.5, 0.0], "target": [-1.5, 0.0, -1.5], "yfov_deg": 40, "path": "slide" })",
      R"(
  "paths": { "slide": { "keys": [
    { "time": 0, "position": [-1.5, 1.5, 0.0], "target": [-1.5, 0.0, -1.5], "yfov_deg": 40 },
    { "time": 1.0667, "position": [1.5, 1.5, 0.0], "target": [1.5, 0.0, -1.5], "yfov_deg": 40 } ] } },)",
      "", true, "sun over a slab, camera sliding");
}

// The same slab turning about its vertical axis at 90 degrees a second (1.5 degrees a frame, 8
// cm a frame 3 m from the axis) under a still camera: the media history follows the medium's
// motion (GpuVolume.motion), and the mean must still be the closed form's.
TEST_F(VolumeScatterTest, DirectionalLightOverASlabThatTurns) {
  expect_sun_over_a_slab(
      R"({ "position": [0.0, 1.5, 0.0], "target": [0.0, 0.0, -1.5], "yfov_deg": 40 })", "",
      R"(, "behaviour": { "type": "rotate", "axis": [0, 1, 0], "speed_deg": 90 })", true,
      "sun over a slab, slab turning");
}

// A uniform sky (an equirectangular map of radiance Le) over the slab, seen from inside it: the
// light that only the environment and the phase function reach (the reference's phase-sampled
// technique, MIS'd with light sampling, carries it where a direction finds the sky). The floor
// is lit through the slab, E = 2 pi Le integral_0^1 mu e^{-s_t H / mu} dmu, and the ray gains
//   s_s Le integral over the upper hemisphere of phase(d.w) e^{-s_t (H - z0) / mu}
//        (1 - e^{-k D}) / k dw,  k = s_t (1 - d.y / mu)
// (the lower hemisphere is the floor: single scattering takes no light from a surface). The
// slab reaches 40 m out, so paths leaving through its sides carry e^-12.
TEST_F(VolumeScatterTest, UniformSkyOverAHomogeneousSlabSeenFromInside) {
  const Fog fog{.scattering = 0.2, .absorption = 0.1, .anisotropy = 0.5};
  const double top = 2.0;
  const float sky = 0.8f;
  runtime::ImageRGBA32F map(8, 4);
  for (std::uint32_t y = 0; y < 4; ++y)
    for (std::uint32_t x = 0; x < 8; ++x) {
      float* p = map.at(x, y);
      p[0] = p[1] = p[2] = sky;
      p[3] = 1.0f;
    }
  runtime::write_image(test::process_scratch_dir() / "lantern_volume_uniform_sky.exr", map);
  auto level_json = [&](const std::string& volume) {
    return test::with_volume(R"({
  "materials": { "floor": { "base_color": [0.6, 0.6, 0.6], "roughness": 1.0 } },
  "primitives": [ { "type": "plane", "size": [400, 400], "material": "floor" } ],
  "environment": { "file": "lantern_volume_uniform_sky.exr" },
  "camera": { "position": [0.0, 1.5, 0.0], "target": [0.0, 0.0, -1.5], "yfov_deg": 40 } })",
                             volume);
  };
  const auto clear = test::level_from_json("sky_clear", level_json(""));
  const auto foggy =
      test::level_from_json("sky_fog", level_json(fog.entry("[80, 3, 80]", 0.5, -1.0)));
  const double s_t = fog.extinction();
  const double floor_share =
      2.0 * simpson([&](double mu) { return mu > 0.0 ? mu * std::exp(-s_t * top / mu) : 0.0; },
                    0.0, 1.0, 400);
  // The in-scattered part of each pixel, integrated once.
  std::vector<double> inscattered(std::size_t{kWidth} * kHeight);
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const test::PixelRay ray = test::pixel_ray(*clear, kWidth, kHeight, x, y);
      const double z0 = ray.origin.y;
      const double distance = -z0 / ray.dir.y;
      // Over the upper hemisphere in (mu, phi); phi from the ray's own azimuth.
      const glm::dvec3 up(0.0, 1.0, 0.0);
      const glm::dvec3 side = glm::normalize(glm::cross(up, ray.dir));
      const glm::dvec3 ahead = glm::cross(side, up);
      const double along_ray = simpson(
          [&](double mu) {
            if (!(mu > 0.0)) return 0.0;
            const double k = s_t * (1.0 - ray.dir.y / mu);
            const double along =
                std::exp(-s_t * (top - z0) / mu) * (1.0 - std::exp(-k * distance)) / k;
            const double sine = std::sqrt(std::max(0.0, 1.0 - mu * mu));
            return along * simpson(
                               [&](double phi) {
                                 const glm::dvec3 w =
                                     mu * up + sine * (std::cos(phi) * ahead + std::sin(phi) * side);
                                 return double(gpu::hg_phase(float(glm::dot(ray.dir, w)),
                                                             float(fog.anisotropy)));
                               },
                               0.0, 2.0 * M_PI, 32);
          },
          0.0, 1.0, 64);
      inscattered[std::size_t{y} * kWidth + x] = fog.scattering * sky * along_ray;
    }
  // The reference only: this light reaches the media through the phase-sampled technique, which
  // only the reference has (64 frames of ReSTIR over a uniform sky in fog still spread +-2%:
  // its frames are correlated).
  expect_matches(
      *clear, *foggy,
      [&](std::uint32_t x, std::uint32_t y, double clear_value) {
        const test::PixelRay ray = test::pixel_ray(*clear, kWidth, kHeight, x, y);
        const double floor = clear_value * floor_share * std::exp(-s_t * (-ray.origin.y / ray.dir.y));
        return floor + inscattered[std::size_t{y} * kWidth + x];
      },
      "uniform sky over a slab", {.reference_only = true, .reference_spp = 256});
}

TEST_F(VolumeScatterTest, PointLightInAThinHomogeneousMedium) {
  const Fog fog{.scattering = 0.05, .absorption = 0.05, .anisotropy = -0.4};
  const double intensity = 20.0;  // test::kFloorUnderPointLight's light
  const glm::dvec3 light = test::kFloorLight;
  auto level_json = [](const std::string& volume) {
    return test::with_volume(test::kFloorUnderPointLight, volume);
  };
  const auto clear = test::level_from_json("thin_clear", level_json(""));
  const auto foggy =
      test::level_from_json("thin_fog", level_json(fog.entry("[40, 20, 40]", 0.5, -5.0)));
  const double s_t = fog.extinction();
  expect_matches(
      *clear, *foggy,
      [&](std::uint32_t x, std::uint32_t y, double clear_value) {
        const test::PixelRay ray = test::pixel_ray(*clear, kWidth, kHeight, x, y);
        const glm::dvec3 p = test::floor_point(*clear, kWidth, kHeight, x, y);
        const double distance = glm::length(p - ray.origin);
        const double surface =
            clear_value * std::exp(-s_t * (distance + glm::length(light - p)));
        const double delta = glm::dot(light - ray.origin, ray.dir);
        const double h = glm::length(light - (ray.origin + delta * ray.dir));
        auto along = [&](double theta) {
          const double t = delta + h * std::tan(theta);
          const glm::dvec3 to_light = light - (ray.origin + t * ray.dir);
          const double r = glm::length(to_light);
          const double phase = gpu::hg_phase(float(glm::dot(ray.dir, to_light / r)),
                                             float(fog.anisotropy));
          return fog.scattering * phase * intensity * std::exp(-s_t * (t + r)) / h;
        };
        const double inscattered =
            simpson(along, std::atan(-delta / h), std::atan((distance - delta) / h), 2000);
        return surface + inscattered;
      },
      "point light in thin fog");
}

// Heterogeneous media with no closed form: a smoke plume inside a ground-fog bank (two
// overlapping generated volumes) lit by every light kind (a point light, a spot, the sun and an
// emissive quad). Baseline and ReSTIR (64 static frames; ReSTIR with its temporal and spatial
// media reuse) must agree with the reference (256 samples per pixel) on the image mean within
// 1.5% and on each half of the image within 3%: the reference is unbiased, so a bias in the media
// reservoirs' MIS weights, shifts or cheap targets shows here.
TEST_F(VolumeScatterTest, HeterogeneousMediaAgreeWithTheReference) {
  const std::string json = R"({
  "materials": { "ground": { "base_color": [0.5, 0.5, 0.5], "roughness": 0.9 },
                 "panel": { "base_color": [0.02, 0.02, 0.02], "roughness": 0.9 } },
  "primitives": [
    { "type": "plane", "size": [12, 12], "material": "ground" },
    { "type": "emissive_quad_grid", "name": "sign", "material": "panel",
      "origin": [-1.5, 1.2, -1.5], "u": [0.4, 0, 0], "v": [0, 0.3, 0], "counts": [2, 1], "size": [0.3, 0.2],
      "color": [1.0, 0.4, 0.2], "radiance": { "min": 40, "max": 40, "pattern": "log", "levels": 1 } } ],
  "lights": [
    { "type": "point", "position": [0.8, 1.2, 0.3], "color": [1, 0.9, 0.7], "intensity": 6 },
    { "type": "spot", "position": [-1.5, 3.0, 1.0], "target": [0, 0, 0], "intensity": 30,
      "inner_cone_deg": 15, "outer_cone_deg": 30 },
    { "type": "directional", "direction": [0.3, -1.0, -0.2], "color": [0.6, 0.7, 1.0], "intensity": 0.5 } ],
  "volumes": [
    { "name": "fog", "generate": { "type": "ground_fog", "seed": 2, "size": [8, 2, 8], "voxel_size": 0.25 },
      "density_scale": 0.5, "scattering": [0.8, 0.8, 0.8], "absorption": [0.05, 0.05, 0.05], "anisotropy": 0.2 },
    { "name": "plume", "generate": { "type": "smoke_plume", "seed": 3, "size": [1.5, 3, 1.5], "voxel_size": 0.1 },
      "density_scale": 2.0, "scattering": [0.6, 0.6, 0.6], "absorption": [0.3, 0.3, 0.3], "anisotropy": 0.5 } ],
  "camera": { "position": [0.0, 1.4, 4.5], "target": [0.0, 0.9, 0.0], "yfov_deg": 50 }
})";
  const auto level = test::level_from_json("media_mix", json);
  ASSERT_EQ(level->volumes.size(), 2u);
  auto render = [&](const char* integrator) {
    const bool reference = std::string(integrator) == "reference";
    return test::render_volume_level(device, shaders, *level, integrator,
                                     {.width = kWidth,
                                      .height = kHeight,
                                      .frames = reference ? 8u : 64u,
                                      .spp = 128,
                                      .seed = 7});
  };
  // Green-channel sums over the whole image and its left and right halves.
  auto sums = [&](const runtime::ImageRGBA32F& image) {
    std::array<double, 3> s{0.0, 0.0, 0.0};
    for (std::uint32_t y = 0; y < kHeight; ++y)
      for (std::uint32_t x = 0; x < kWidth; ++x) {
        const double v = image.pixels[4 * (std::size_t{y} * kWidth + x) + 1];
        s[0] += v;
        s[x < kWidth / 2 ? 1 : 2] += v;
      }
    return s;
  };
  const auto expected = sums(render("reference"));
  for (const char* integrator : {"baseline", "restir"}) {
    const auto got = sums(render(integrator));
    std::printf("[volume] heterogeneous media, %s / reference: image %.4f, left %.4f, right %.4f\n",
                integrator, got[0] / expected[0], got[1] / expected[1], got[2] / expected[2]);
    EXPECT_NEAR(got[0] / expected[0], 1.0, 0.015) << integrator;
    EXPECT_NEAR(got[1] / expected[1], 1.0, 0.03) << integrator;
    EXPECT_NEAR(got[2] / expected[2], 1.0, 0.03) << integrator;
  }
}

// Numerical extremes of the media: a camera inside smoke of extinction 10^5 1/m (every tracking
// walk hits its step cap), a point light on the camera's axis inside thin fog (equiangular
// sampling with the light on the ray), the light at the camera itself (the in-scattered
// radiance integral diverges there: huge but finite samples), at intensities 10^-3 and 10^5.
// Every integrator's frames (ReSTIR's with its media history) stay finite and non-negative, and
// the 10^8 change of intensity scales ReSTIR's image by 10^8 (no overflow, underflow or clamp in
// the reservoirs' weights).
TEST_F(VolumeScatterTest, ExtremeMediaStayFinite) {
  auto level_json = [](double density, double intensity, const std::string& light) {
    return R"({
  "materials": { "floor": { "base_color": [0.6, 0.6, 0.6], "roughness": 1.0 } },
  "primitives": [ { "type": "plane", "size": [6, 6], "material": "floor" } ],
  "lights": [ { "type": "point", "position": )" + light + R"(, "color": [1, 1, 1], "intensity": )" +
           std::to_string(intensity) + R"( } ],
  "camera": { "position": [0.0, 2.0, 0.0], "target": [0.0, 0.0, 0.0001], "yfov_deg": 40 },
  "volumes": [ { "name": "fog", "generate": { "type": "constant", "size": [8, 4, 8], "voxel_size": 0.5 },
    "density_scale": )" + std::to_string(density) + R"(, "scattering": [0.5, 0.5, 0.5], "absorption": [0.5, 0.5, 0.5] } ] })";
  };
  struct Case {
    const char* name;
    double density;
    std::string light;
  };
  const Case cases[] = {
      {"dense smoke", 1e5, "[0.5, 1.0, 0.2]"},
      {"light on the axis", 0.05, "[0.0, 1.0, 0.00005]"},
      {"light at the camera", 0.05, "[0.0, 2.0, 0.0]"},
  };
  for (const Case& c : cases) {
    double means[2] = {0.0, 0.0};
    for (int scale = 0; scale < 2; ++scale) {
      const double intensity = scale == 0 ? 1e-3 : 1e5;
      const auto level = test::level_from_json("media_extreme", level_json(c.density, intensity, c.light));
      for (const char* integrator : {"baseline", "reference", "restir"}) {
        const runtime::ImageRGBA32F image = test::render_volume_level(
            device, shaders, *level, integrator,
            {.width = 32, .height = 18, .frames = 4, .spp = 2, .seed = 2});
        double sum = 0.0;
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
          ASSERT_TRUE(std::isfinite(image.pixels[i])) << c.name << ", " << integrator;
          ASSERT_GE(image.pixels[i], 0.0f) << c.name << ", " << integrator;
          if (i % 4 != 3) sum += image.pixels[i];  // rgb, not alpha
        }
        if (std::string(integrator) == "restir") means[scale] = sum;
      }
    }
    std::printf("[volume] extreme media, %s: ReSTIR image sum %.4g at 1e-3, %.4g at 1e5\n", c.name,
                means[0], means[1]);
    // The opaque smoke is black at both scales (the camera sees nothing through 10^5 1/m).
    if (c.density < 1.0) {
      ASSERT_GT(means[0], 0.0) << c.name;
      EXPECT_NEAR(means[1] / means[0] / 1e8, 1.0, 1e-3) << c.name << ": not scale invariant";
    }
  }
}

}  // namespace
}  // namespace lantern
