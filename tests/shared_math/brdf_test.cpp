// The shared BRDF: energy never exceeds 1 (white furnace), reciprocity, and the GGX VNDF and
// cosine samplers agree with their pdfs (integral and histogram).
#include "shared/brdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <vector>

#include "shared/rng.h"
#include "statistics.h"

namespace lantern::gpu {
namespace {

const vec3 kNormal = normalize(vec3(0.2f, -0.3f, 0.9f));  // not axis-aligned: exercises the basis

vec3 view_at(float cos_theta) {
  vec3 t;
  vec3 b;
  orthonormal_basis(kNormal, t, b);
  float sin_theta = std::sqrt(1.0f - cos_theta * cos_theta);
  return normalize(sin_theta * t + cos_theta * kNormal);
}

vec3 uniform_sphere(vec2 u) {
  float z = 1.0f - 2.0f * u.x;
  float r = std::sqrt(max(0.0f, 1.0f - z * z));
  float phi = kTwoPi * u.y;
  return vec3(r * std::cos(phi), r * std::sin(phi), z);
}

// Directional albedo of a white material: the integral of f cos over the hemisphere, estimated
// with a 50/50 mixture of cosine and VNDF sampling (one-sample MIS over both pdfs).
test::RunningStats white_furnace(float cos_view, float roughness, float metallic, float specular,
                                 int samples, uint& rng) {
  vec3 v = view_at(cos_view);
  test::RunningStats stats;
  for (int i = 0; i < samples; ++i) {
    vec2 u = rng_next_vec2(rng);
    vec3 l = rng_next_float(rng) < 0.5f ? cosine_sample_hemisphere(kNormal, u)
                                        : ggx_vndf_sample(kNormal, v, roughness, u);
    float pdf =
        0.5f * cosine_hemisphere_pdf(kNormal, l) + 0.5f * ggx_vndf_pdf(kNormal, v, l, roughness);
    vec3 f_cos = brdf_eval(kNormal, v, l, vec3(1.0f), roughness, metallic, specular);
    stats.add(pdf > 0.0f ? double(f_cos.x) / double(pdf) : 0.0);
  }
  return stats;
}

TEST(Brdf, WhiteFurnaceNeverGainsEnergy) {
  uint rng = rng_init(uvec2(1u), 0u, 42u, 0u);
  for (float roughness : {0.05f, 0.25f, 0.5f, 0.75f, 1.0f})
    for (float cos_view : {1.0f, 0.5f, 0.1f})
      for (int material = 0; material < 3; ++material) {
        float metallic = material == 1 ? 1.0f : 0.0f;
        float specular = material == 2 ? 0.0f : 1.0f;
        test::RunningStats e = white_furnace(cos_view, roughness, metallic, specular, 100000, rng);
        double limit = 1.0 + 3.0 * e.standard_error() + 1e-3;
        std::printf("furnace rough %.2f cos_v %.1f %-10s: %.4f +- %.4f\n", roughness, cos_view,
                    material == 0   ? "dielectric"
                    : material == 1 ? "metal"
                                    : "lambert",
                    e.mean(), e.standard_error());
        EXPECT_LE(e.mean(), limit)
            << "roughness " << roughness << " cos_v " << cos_view << " material " << material;
        if (material == 2) {  // pure Lambert reflects everything: checks the estimator itself
          EXPECT_NEAR(e.mean(), 1.0, 3.0 * e.standard_error() + 1e-3);
        }
        if (material == 1 && roughness <= 0.05f) {  // smooth white metal loses almost nothing
          EXPECT_GT(e.mean(), 0.97);
        }
      }
}

TEST(Brdf, Reciprocal) {
  uint rng = rng_init(uvec2(2u), 0u, 43u, 0u);
  for (int i = 0; i < 20000; ++i) {
    vec3 v = cosine_sample_hemisphere(kNormal, rng_next_vec2(rng));
    vec3 l = cosine_sample_hemisphere(kNormal, rng_next_vec2(rng));
    float n_dot_v = dot(kNormal, v);
    float n_dot_l = dot(kNormal, l);
    if (n_dot_v < 1e-3f || n_dot_l < 1e-3f) continue;
    float red = rng_next_float(rng);
    float green = rng_next_float(rng);
    vec3 albedo(red, green, rng_next_float(rng));
    float roughness = rng_next_float(rng);
    float metallic = rng_next_float(rng);
    float specular = rng_next_float(rng);
    vec3 f_vl = brdf_eval(kNormal, v, l, albedo, roughness, metallic, specular) / n_dot_l;
    vec3 f_lv = brdf_eval(kNormal, l, v, albedo, roughness, metallic, specular) / n_dot_v;
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(f_vl[c], f_lv[c], 2e-4f * max(f_vl[c], 1.0f)) << "sample " << i;
  }
}

TEST(Brdf, SpecularZeroIsPureLambert) {
  vec3 v = view_at(0.7f);
  vec3 l = view_at(0.4f);
  vec3 albedo(0.2f, 0.5f, 0.8f);
  vec3 f = brdf_eval(kNormal, v, l, albedo, 0.3f, 0.0f, 0.0f);
  vec3 lambert = albedo * kInvPi * dot(kNormal, l);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(f[c], lambert[c]);
}

TEST(Brdf, VndfPdfIntegratesToOne) {
  uint rng = rng_init(uvec2(3u), 0u, 44u, 0u);
  for (float roughness : {0.3f, 0.6f, 1.0f})
    for (float cos_view : {0.9f, 0.3f}) {
      vec3 v = view_at(cos_view);
      test::RunningStats integral;
      for (int i = 0; i < 400000; ++i) {
        vec3 l = uniform_sphere(rng_next_vec2(rng));
        integral.add(double(ggx_vndf_pdf(kNormal, v, l, roughness)) * 4.0 * 3.14159265358979);
      }
      EXPECT_NEAR(integral.mean(), 1.0, 4.0 * integral.standard_error() + 2e-3)
          << "roughness " << roughness << " cos_v " << cos_view;
    }
}

// Histogram of VNDF-sampled directions against the pdf integrated over each bin; bins are
// equal-area cells in (z = n.l, phi) of the normal's frame.
TEST(Brdf, VndfSamplesMatchPdfHistogram) {
  constexpr int kZBins = 10;
  constexpr int kPhiBins = 12;
  constexpr int kSub = 24;  // quadrature points per bin side
  constexpr int kSamples = 1000000;
  const float roughness = 0.6f;
  vec3 v = view_at(0.5f);
  vec3 t;
  vec3 b;
  orthonormal_basis(kNormal, t, b);
  auto bin_of = [&](vec3 l) {
    float z = clamp(dot(l, kNormal), -1.0f, 1.0f);
    float phi = std::atan2(dot(l, b), dot(l, t));
    if (phi < 0.0f) phi += kTwoPi;
    int zi = min(int((z + 1.0f) * 0.5f * kZBins), kZBins - 1);
    int pi = min(int(phi / kTwoPi * kPhiBins), kPhiBins - 1);
    return static_cast<std::size_t>(zi * kPhiBins + pi);
  };
  std::vector<double> probability(kZBins * kPhiBins, 0.0);
  const double dz = 2.0 / kZBins / kSub;
  const double dphi = 2.0 * 3.14159265358979 / kPhiBins / kSub;
  for (int zi = 0; zi < kZBins * kSub; ++zi)
    for (int pi = 0; pi < kPhiBins * kSub; ++pi) {
      double z = -1.0 + (zi + 0.5) * dz;
      double phi = (pi + 0.5) * dphi;
      double r = std::sqrt(1.0 - z * z);
      vec3 l = normalize(float(r * std::cos(phi)) * t + float(r * std::sin(phi)) * b +
                         float(z) * kNormal);
      probability[bin_of(l)] += double(ggx_vndf_pdf(kNormal, v, l, roughness)) * dz * dphi;
    }
  uint rng = rng_init(uvec2(4u), 0u, 45u, 0u);
  std::vector<std::uint64_t> counts(probability.size(), 0);
  for (int i = 0; i < kSamples; ++i)
    counts[bin_of(ggx_vndf_sample(kNormal, v, roughness, rng_next_vec2(rng)))]++;
  double total_probability = 0.0;
  for (double p : probability) total_probability += p;
  EXPECT_NEAR(total_probability, 1.0, 2e-3);
  for (double& p : probability) p /= total_probability;
  int dof = 0;
  double chi2 = test::chi_square(counts, probability, dof);
  double critical = test::chi_square_critical(dof, test::kZ1e3);
  std::printf("vndf histogram: chi2 %.1f (dof %d, critical %.1f)\n", chi2, dof, critical);
  EXPECT_LT(chi2, critical);
}

TEST(Brdf, CosineSamplesLieInTheHemisphereWithMatchingPdf) {
  uint rng = rng_init(uvec2(5u), 0u, 46u, 0u);
  test::RunningStats mean_cos;
  for (int i = 0; i < 200000; ++i) {
    vec3 l = cosine_sample_hemisphere(kNormal, rng_next_vec2(rng));
    ASSERT_NEAR(length(l), 1.0f, 1e-4f);
    ASSERT_GE(dot(l, kNormal), -1e-6f);
    mean_cos.add(dot(l, kNormal));
  }
  // E[cos] under pdf cos/pi is 2/3.
  EXPECT_NEAR(mean_cos.mean(), 2.0 / 3.0, 4.0 * mean_cos.standard_error());
}

}  // namespace
}  // namespace lantern::gpu
