// Environment map importance sampling (shaders/shared/environment.h, built by
// lighting/lights/environment_map.h), on the CPU with the very code the GPU runs: the map
// convention, pdf integrating to 1 over the sphere, a chi-square test of sampled directions
// against the pdf (per half-texel, so the distribution inside a texel is checked too), sample
// pdf/radiance equal to the pdf/lookup of the sampled direction, pdf proportional to luminance,
// black maps, and the light-selection probability.
#include "shared/environment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <random>

#include "engine/core/error.h"
#include "lighting/lights/environment_map.h"
#include "shared/color.h"
#include "tests/shared_math/statistics.h"

namespace lantern {
namespace {

using lighting::EnvironmentDistribution;

constexpr double kPiD = 3.14159265358979323846;

// A W x H map with smoothly varying, strongly non-uniform coloured radiance and one black row.
runtime::ImageRGBA32F test_map(std::uint32_t w, std::uint32_t h) {
  runtime::ImageRGBA32F image(w, h);
  for (std::uint32_t y = 0; y < h; ++y) {
    for (std::uint32_t x = 0; x < w; ++x) {
      float* p = image.at(x, y);
      const float s =
          0.05f + static_cast<float>((x * 7 + y * 13) % 11) + (x == 3 && y == 2 ? 200.0f : 0.0f);
      p[0] = s;
      p[1] = 0.5f * s + static_cast<float>(y);
      p[2] = static_cast<float>(x % 3);
      p[3] = 1.0f;
      if (y == h - 2) p[0] = p[1] = p[2] = 0.0f;
    }
  }
  return image;
}

const glm::quat kRotation = glm::quat(glm::radians(glm::vec3(20.0f, 70.0f, -10.0f)));

// Map-space (u, v) of a world direction, computed independently of environment.h: Blender's
// equirectangular lookup (Cycles direction_to_equirectangular: u = 1/2 - atan2(y, x) / 2pi,
// v = 1 - acos(z) / pi from the image bottom) on the direction in Blender's Z-up axes, which are
// our (x, -z, y) (the glTF axis conversion); our rows count from the top.
glm::dvec2 reference_uv(glm::dvec3 world, const glm::quat& rotation) {
  const glm::dvec3 d = glm::inverse(glm::dquat(rotation)) * world;
  const glm::dvec3 b(d.x, -d.z, d.y);  // Blender axes
  const double u = 0.5 - std::atan2(b.y, b.x) / (2.0 * kPiD);
  const double v_blender = 1.0 - std::acos(glm::clamp(b.z, -1.0, 1.0)) / kPiD;
  return {u, 1.0 - v_blender};
}

// Blender's world texture: the image centre faces Blender +X (our +X), u = 0.25 Blender +Y (our
// -Z), u = 0.75 Blender -Y (our +Z); the top row is straight up.
TEST(EnvironmentMap, ConventionIsBlendersWorldTexture) {
  const glm::vec2 centre = gpu::env_direction_to_uv(glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_NEAR(centre.x, 0.5f, 1e-6f);
  EXPECT_NEAR(centre.y, 0.5f, 1e-6f);
  EXPECT_NEAR(gpu::env_direction_to_uv(glm::vec3(0.0f, 0.0f, -1.0f)).x, 0.25f, 1e-6f);
  EXPECT_NEAR(gpu::env_direction_to_uv(glm::vec3(0.0f, 0.0f, 1.0f)).x, 0.75f, 1e-6f);
  EXPECT_NEAR(gpu::env_direction_to_uv(glm::vec3(-1.0f, 0.0f, -1e-6f)).x, 0.0f, 1e-5f);
  EXPECT_NEAR(gpu::env_direction_to_uv(glm::vec3(0.0f, 1.0f, 0.0f)).y, 0.0f, 1e-6f);
  EXPECT_NEAR(gpu::env_direction_to_uv(glm::vec3(0.0f, -1.0f, 0.0f)).y, 1.0f, 1e-6f);
  for (const glm::vec3 d : {glm::vec3(0.3f, 0.5f, -0.8f), glm::vec3(-0.7f, -0.2f, 0.1f)}) {
    const glm::vec3 n = glm::normalize(d);
    const glm::dvec2 ref = reference_uv(glm::dvec3(n), glm::quat(1, 0, 0, 0));
    EXPECT_NEAR(gpu::env_direction_to_uv(n).x, ref.x, 1e-5);
    EXPECT_NEAR(gpu::env_direction_to_uv(n).y, ref.y, 1e-5);
    const glm::vec3 back = gpu::env_uv_to_direction(gpu::env_direction_to_uv(n));
    EXPECT_NEAR(glm::length(back - n), 0.0f, 1e-5f);
  }
}

TEST(EnvironmentMap, LookupReturnsTheTexelOfTheDirection) {
  const auto image = test_map(16, 8);
  const EnvironmentDistribution env(image, 2.0f, kRotation);
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const double z = 2.0 * uni(gen) - 1.0;
    const double phi = 2.0 * kPiD * uni(gen);
    const double r = std::sqrt(1.0 - z * z);
    const glm::dvec3 dir(r * std::cos(phi), z, r * std::sin(phi));
    const glm::dvec2 uv = reference_uv(dir, kRotation);
    const double fx = uv.x * 16.0;
    const double fy = uv.y * 8.0;
    // Skip directions within rounding distance of a texel border.
    if (std::abs(fx - std::round(fx)) < 1e-4 || std::abs(fy - std::round(fy)) < 1e-4) continue;
    const auto x = static_cast<std::uint32_t>(std::min(fx, 15.0));
    const auto y = static_cast<std::uint32_t>(std::min(fy, 7.0));
    const glm::vec3 got = gpu::env_radiance(env.view(), env.header(), glm::vec3(dir));
    const float* p = image.at(x, y);
    EXPECT_EQ(got, 2.0f * glm::vec3(p[0], p[1], p[2])) << "direction " << i;
    ++checked;
  }
  EXPECT_GT(checked, 1900);
}

TEST(EnvironmentMap, PdfIntegratesToOneOverTheSphere) {
  const auto image = test_map(16, 8);
  const EnvironmentDistribution env(image, 1.0f, kRotation);
  ASSERT_EQ(env.header().size.z, 1u);
  // Midpoint rule on a grid uniform in (phi, cos theta): equal solid angle per cell. The pdf is
  // piecewise constant on texels, so the error comes only from cells straddling borders.
  const int n_phi = 512;
  const int n_z = 512;
  const double cell = 4.0 * kPiD / (n_phi * n_z);
  double integral = 0.0;
  for (int i = 0; i < n_z; ++i) {
    const double z = -1.0 + 2.0 * (i + 0.5) / n_z;
    const double r = std::sqrt(1.0 - z * z);
    for (int j = 0; j < n_phi; ++j) {
      const double phi = 2.0 * kPiD * (j + 0.5) / n_phi;
      const glm::vec3 dir(r * std::cos(phi), z, r * std::sin(phi));
      integral += gpu::env_pdf(env.view(), env.header(), dir) * cell;
    }
  }
  EXPECT_NEAR(integral, 1.0, 2e-3);
}

TEST(EnvironmentMap, SampledDirectionsMatchThePdfChiSquare) {
  constexpr std::uint32_t kW = 16;
  constexpr std::uint32_t kH = 8;
  const auto image = test_map(kW, kH);
  const EnvironmentDistribution env(image, 1.0f, kRotation);
  // Bins: each texel split in two in phi and in two in cos(theta) (equal solid angles), so both
  // the texel choice and the placement inside the texel are tested. Probabilities from the
  // texels' luminance and exact solid angles, computed here independently.
  std::vector<double> texel_weight(kW * kH);
  double total = 0.0;
  for (std::uint32_t y = 0; y < kH; ++y) {
    const double c0 = std::cos(kPiD * y / kH);
    const double c1 = std::cos(kPiD * (y + 1) / kH);
    for (std::uint32_t x = 0; x < kW; ++x) {
      const float* p = image.at(x, y);
      const double w = gpu::luminance(glm::vec3(p[0], p[1], p[2])) * (c0 - c1);
      texel_weight[y * kW + x] = w;
      total += w;
    }
  }
  std::vector<double> probability(4 * kW * kH);
  for (std::uint32_t i = 0; i < kW * kH; ++i) {
    for (int k = 0; k < 4; ++k) probability[4 * i + k] = texel_weight[i] / total / 4.0;
  }
  std::vector<std::uint64_t> observed(probability.size(), 0);
  std::mt19937 gen(11);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  const int samples = 400000;
  int pdf_mismatch = 0;
  int radiance_mismatch = 0;
  for (int i = 0; i < samples; ++i) {
    glm::vec4 u;
    for (int c = 0; c < 4; ++c) u[c] = std::min(uni(gen), 0.99999994f);
    glm::vec3 dir;
    glm::vec3 radiance;
    const float pdf = gpu::env_sample(env.view(), env.header(), u, dir, radiance);
    ASSERT_GT(pdf, 0.0f);
    ASSERT_TRUE(std::isfinite(pdf));
    const glm::dvec2 uv = reference_uv(glm::dvec3(dir), kRotation);
    const auto x = static_cast<std::uint32_t>(std::clamp(uv.x * kW, 0.0, kW - 1e-9));
    const auto y = static_cast<std::uint32_t>(std::clamp(uv.y * kH, 0.0, kH - 1e-9));
    const double fx = uv.x * kW - x;
    const double c0 = std::cos(kPiD * y / kH);
    const double c1 = std::cos(kPiD * (y + 1) / kH);
    const double z = std::cos(uv.y * kPiD);
    const int sub = (fx >= 0.5 ? 1 : 0) + (z <= 0.5 * (c0 + c1) ? 2 : 0);
    ++observed[4 * (y * kW + x) + sub];
    // The pdf and lookup of the sampled direction agree with what the sample returned (up to
    // directions that land within rounding of a texel border).
    const float pdf_again = gpu::env_pdf(env.view(), env.header(), dir);
    if (std::abs(pdf_again - pdf) > 1e-4f * pdf) ++pdf_mismatch;
    if (gpu::env_radiance(env.view(), env.header(), dir) != radiance) ++radiance_mismatch;
  }
  for (std::size_t i = 0; i < probability.size(); ++i) {
    if (probability[i] == 0.0) {
      EXPECT_EQ(observed[i], 0u) << "bin " << i << " has probability 0";
    }
  }
  int dof = 0;
  const double chi2 = test::chi_square(observed, probability, dof);
  EXPECT_LT(chi2, test::chi_square_critical(dof, test::kZ1e3)) << "dof " << dof;
  EXPECT_LT(pdf_mismatch, samples / 1000);
  EXPECT_LT(radiance_mismatch, samples / 1000);
}

TEST(EnvironmentMap, PdfIsProportionalToLuminance) {
  const auto image = test_map(16, 8);
  const EnvironmentDistribution env(image, 3.0f, kRotation);
  std::mt19937 gen(5);
  std::uniform_real_distribution<float> uni(0.0f, 0.999f);
  // pdf = lum / (4 pi mean luminance): the mean luminance is the normaliser.
  const double norm = 4.0 * kPiD * env.mean_luminance();
  for (int i = 0; i < 500; ++i) {
    glm::vec3 dir;
    glm::vec3 radiance;
    const float pdf = gpu::env_sample(
        env.view(), env.header(), glm::vec4(uni(gen), uni(gen), uni(gen), uni(gen)), dir, radiance);
    EXPECT_NEAR(pdf * norm, gpu::luminance(radiance), 1e-4 * gpu::luminance(radiance));
  }
}

TEST(EnvironmentMap, ConstantMapHasUniformPdfAndMeanRadiance) {
  runtime::ImageRGBA32F image(8, 4);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = 0.25f;
  const EnvironmentDistribution env(image, 2.0f, glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
  EXPECT_NEAR(env.mean_luminance(), 0.5f, 1e-5f);
  for (const glm::vec3 dir :
       {glm::vec3(0, 1, 0), glm::vec3(0.3f, -0.9f, 0.1f), glm::vec3(-1, 0, 0)}) {
    EXPECT_NEAR(gpu::env_pdf(env.view(), env.header(), glm::normalize(dir)), 1.0 / (4.0 * kPiD),
                1e-5);
  }
  EXPECT_NEAR(env.power_estimate(2.0f), 4.0 * kPiD * 0.5 * kPiD * 4.0, 1e-3);
}

TEST(EnvironmentMap, BlackMapIsNotSampled) {
  runtime::ImageRGBA32F image(4, 2);
  const EnvironmentDistribution env(image, 1.0f, glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
  EXPECT_EQ(env.header().size.z, 0u);
  glm::vec3 dir;
  glm::vec3 radiance;
  EXPECT_EQ(gpu::env_sample(env.view(), env.header(), glm::vec4(0.5f), dir, radiance), 0.0f);
  EXPECT_EQ(radiance, glm::vec3(0.0f));
  EXPECT_EQ(gpu::env_pdf(env.view(), env.header(), glm::vec3(0, 1, 0)), 0.0f);
  EXPECT_EQ(env.power_estimate(1.0f), 0.0);
}

TEST(EnvironmentMap, RejectsBadTexelsAndEmptyImages) {
  runtime::ImageRGBA32F image(4, 2);
  image.at(1, 1)[2] = std::nanf("");
  EXPECT_THROW(EnvironmentDistribution(image, 1.0f, glm::quat(1, 0, 0, 0)), InputError);
  image.at(1, 1)[2] = -1.0f;
  EXPECT_THROW(EnvironmentDistribution(image, 1.0f, glm::quat(1, 0, 0, 0)), InputError);
  EXPECT_THROW(EnvironmentDistribution(runtime::ImageRGBA32F(), 1.0f, glm::quat(1, 0, 0, 0)),
               InputError);
}

TEST(EnvironmentMap, SelectionProbabilityFollowsPower) {
  EXPECT_FLOAT_EQ(lighting::environment_selection_probability(1.0, 3.0), 0.25f);
  EXPECT_FLOAT_EQ(lighting::environment_selection_probability(1.0, 0.0), 1.0f);
  EXPECT_FLOAT_EQ(lighting::environment_selection_probability(0.0, 5.0), 0.0f);
}

}  // namespace
}  // namespace lantern
