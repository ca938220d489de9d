// Unbiasedness of spatial reuse against analytic integrals, per bias-correction mode. Each trial
// runs RIS at a canonical "pixel" and its neighbours, then combines the neighbours' reservoirs
// into the canonical one with the shared MIS helpers, exactly as restir.spatial does. The
// neighbours' targets differ from the canonical one and are zero on part of its support: there
// 1/M is biased (and the test asserts it detects that), balance and pairwise are not.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <initializer_list>
#include <vector>

#include "shared/reservoir.h"
#include "shared/reservoir_mis.h"
#include "shared/rng.h"
#include "statistics.h"

namespace lantern::gpu {
namespace {

// A toy integration problem: lights 0..light_count-1, each with a point (u, v) in [0,1)^2.
// The canonical pixel (0) integrates `integrand`; every pixel resamples by its own `target`.
struct ToyProblem {
  uint light_count = 1u;
  std::vector<uint> candidates_per_pixel;  // pixel 0 is canonical
  std::function<float(uint pixel, uint light, float u, float v)> target;
  std::function<double(uint light, float u, float v)> integrand;
  double analytic = 0.0;
};

float target_of(const ToyProblem& problem, uint pixel, LightSample s) {
  return s.light_index == kInvalidLight ? 0.0f : problem.target(pixel, s.light_index, s.u, s.v);
}

// RIS from a uniform source (pdf 1 / light_count over lights x [0,1)^2) with m_i = 1/N.
Reservoir initial_ris(const ToyProblem& problem, uint pixel, uint& rng) {
  Reservoir r = reservoir_empty();
  uint n = problem.candidates_per_pixel[pixel];
  float source_pdf = 1.0f / float(problem.light_count);
  for (uint i = 0; i < n; ++i) {
    uint light =
        min(uint(rng_next_float(rng) * float(problem.light_count)), problem.light_count - 1u);
    vec2 uv = rng_next_vec2(rng);
    float p_hat = problem.target(pixel, light, uv.x, uv.y);
    float weight = (1.0f / float(n)) * p_hat / source_pdf;
    reservoir_update(r, light_sample_make(light, uv, p_hat), weight, rng_next_float(rng));
  }
  reservoir_finalize(r);
  return r;
}

// m_j of pixel j's sample in the combination at the canonical pixel 0.
float mis_weight(uint mode, const ToyProblem& problem, const std::vector<Reservoir>& pixels,
                 uint j) {
  LightSample y = pixels[j].selected;
  if (y.light_index == kInvalidLight) return 0.0f;
  float k = float(pixels.size() - 1u);
  if (mode == kBiasCorrectionNone) {
    float total = 0.0f;
    for (const Reservoir& r : pixels) total += r.M;
    return mis_weight_none(pixels[j].M, total);
  }
  if (mode == kBiasCorrectionBalance) {
    float denominator = 0.0f;
    for (uint l = 0; l < pixels.size(); ++l)
      denominator += mis_balance_term(pixels[l].M, target_of(problem, l, y));
    return mis_weight_balance(pixels[j].M, target_of(problem, j, y), denominator);
  }
  const Reservoir& canonical = pixels[0];
  float p_c = target_of(problem, 0u, y);
  if (j == 0u) {
    float m = mis_pairwise_canonical_init(k);
    for (uint i = 1; i < pixels.size(); ++i)
      m += mis_pairwise_canonical_term(pixels[i].M, target_of(problem, i, y), canonical.M, p_c, k);
    return m;
  }
  // The neighbour's own target at its sample is the one it stored.
  return mis_pairwise_neighbour(pixels[j].M, y.target_pdf, canonical.M, p_c, k);
}

// One ReSTIR estimate of the canonical pixel's integral: f(y) * W after spatial combination.
double estimate(uint mode, const ToyProblem& problem, uint& rng) {
  std::vector<Reservoir> pixels;
  for (uint p = 0; p < problem.candidates_per_pixel.size(); ++p)
    pixels.push_back(initial_ris(problem, p, rng));
  Reservoir combined = reservoir_empty();
  for (uint j = 0; j < pixels.size(); ++j) {
    float m = mis_weight(mode, problem, pixels, j);
    reservoir_merge(combined, pixels[j], m, target_of(problem, 0u, pixels[j].selected),
                    rng_next_float(rng));
  }
  reservoir_finalize(combined);
  if (!reservoir_has_sample(combined)) return 0.0;
  const LightSample& y = combined.selected;
  return problem.integrand(y.light_index, y.u, y.v) * double(combined.W);
}

test::RunningStats run(uint mode, const ToyProblem& problem, int trials, uint seed) {
  uint rng = rng_init(uvec2(0u), 0u, seed, mode);
  test::RunningStats stats;
  for (int t = 0; t < trials; ++t) stats.add(estimate(mode, problem, rng));
  return stats;
}

// 1-D: one "light", the integral over u of f(u) = (1 + 3u^2) * visibility(u), where visibility
// (0.3 beyond u = 0.8) is not in the target, like shadowing in unshadowed-contribution targets.
// Neighbour 1's target is zero for u < 0.5; neighbour 2's is a different, positive shape.
ToyProblem one_dimensional_problem() {
  ToyProblem problem;
  problem.light_count = 1u;
  problem.candidates_per_pixel = {4u, 2u, 8u};
  problem.target = [](uint pixel, uint, float u, float) -> float {
    if (pixel == 0u) return 1.0f + 3.0f * u * u;
    if (pixel == 1u) return u < 0.5f ? 0.0f : 2.0f * u;
    return 1.0f + u;
  };
  problem.integrand = [](uint, float u, float) -> double {
    double visibility = u < 0.8f ? 1.0 : 0.3;
    return (1.0 + 3.0 * double(u) * double(u)) * visibility;
  };
  auto antiderivative = [](double u) { return u + u * u * u; };
  problem.analytic = (antiderivative(0.8) - antiderivative(0.0)) +
                     0.3 * (antiderivative(1.0) - antiderivative(0.8));
  return problem;
}

// Many lights: 16 lights with per-light power a[l] and a (1 + u v) profile over each light.
// Neighbour 1 cannot see lights 0..5 and weighs the rest differently; neighbour 2 sees only
// even lights. Visibility at the canonical pixel halves every third light.
ToyProblem many_light_problem() {
  static const float power[16] = {1.0f,  4.0f, 0.5f, 2.0f, 8.0f, 0.25f, 3.0f, 1.5f,
                                  0.75f, 5.0f, 2.5f, 0.1f, 6.0f, 1.0f,  0.4f, 3.5f};
  ToyProblem problem;
  problem.light_count = 16u;
  problem.candidates_per_pixel = {4u, 4u, 6u, 2u};
  problem.target = [](uint pixel, uint light, float u, float v) -> float {
    float profile = 1.0f + u * v;
    if (pixel == 0u) return power[light] * profile;
    if (pixel == 1u) return light < 6u ? 0.0f : power[15u - light] * profile;
    if (pixel == 2u) return light % 2u == 0u ? power[light] * (2.0f - u) : 0.0f;
    return power[light] * profile * (light % 4u == 0u ? 3.0f : 1.0f);
  };
  problem.integrand = [](uint light, float u, float v) -> double {
    double visibility = light % 3u == 0u ? 0.5 : 1.0;
    return double(power[light]) * (1.0 + double(u) * double(v)) * visibility;
  };
  for (uint l = 0; l < 16u; ++l)
    problem.analytic += double(power[l]) * 1.25 * (l % 3u == 0u ? 0.5 : 1.0);  // ∫∫(1+uv) = 5/4
  return problem;
}

constexpr int kTrials = 200000;

void check_modes(const char* name, const ToyProblem& problem) {
  const char* mode_names[] = {"none", "balance", "pairwise"};
  for (uint mode : {kBiasCorrectionNone, kBiasCorrectionBalance, kBiasCorrectionPairwise}) {
    test::RunningStats stats = run(mode, problem, kTrials, 2024u);
    double sigma = stats.standard_error();
    double error = stats.mean() - problem.analytic;
    std::printf("%s %-8s: mean %.5f analytic %.5f bias %+.5f (%+.2f%%, %+.1f sigma, sigma %.5f)\n",
                name, mode_names[mode], stats.mean(), problem.analytic, error,
                100.0 * error / problem.analytic, error / sigma, sigma);
    if (mode == kBiasCorrectionNone) {
      // The setup must be able to see bias: 1/M darkens where neighbours cannot sample.
      EXPECT_LT(error, -6.0 * sigma) << name << ": 1/M should be measurably biased here";
    } else {
      EXPECT_LE(std::abs(error), 3.0 * sigma) << name << " " << mode_names[mode];
    }
  }
}

TEST(ReservoirUnbiased, OneDimensionalProblemPerMode) {
  check_modes("1-D", one_dimensional_problem());
}

TEST(ReservoirUnbiased, ManyLightProblemWithDifferentDomainsPerMode) {
  check_modes("many-light", many_light_problem());
}

// Sanity of the harness itself: with a single pixel (no reuse) every mode reduces to plain RIS,
// which is unbiased.
TEST(ReservoirUnbiased, PlainRisWithoutNeighboursIsUnbiased) {
  ToyProblem problem = many_light_problem();
  problem.candidates_per_pixel = {8u};
  test::RunningStats stats = run(kBiasCorrectionNone, problem, kTrials, 99u);
  EXPECT_LE(std::abs(stats.mean() - problem.analytic), 3.0 * stats.standard_error());
}

}  // namespace
}  // namespace lantern::gpu
