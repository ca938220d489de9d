// The shared volume math (shaders/shared/volume.h) on the CPU: chi-square tests of the HG,
// exponential, equiangular and scattering-distance (their MIS) samplers against their own pdfs (bin probabilities integrated
// from the pdf functions, so sampler and pdf must agree), and the ratio / residual ratio
// tracking estimators through a constant medium against exp(-sigma_t d): the mean (4 standard
// errors) and, for ratio tracking, the variance against its closed form; the media reservoirs'
// temporal shift (shared/volume_restir.h). Seeds are fixed.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <functional>
#include <string>
#include <vector>

#include "shared/volume.h"
#include "shared/volume_restir.h"
#include "statistics.h"

namespace lantern::gpu {
namespace {

// Integral of f over [a, b] by composite Simpson with n (even) intervals.
double simpson(const std::function<double(double)>& f, double a, double b, int n = 64) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += f(a + i * h) * (i % 2 ? 4.0 : 2.0);
  return sum * h / 3.0;
}

// Bin probabilities over [lo, hi] from a pdf; chi-square of `samples` against them.
void expect_matches_pdf(const std::vector<double>& samples, double lo, double hi, int bins,
                        const std::function<double(double)>& pdf, const char* what) {
  std::vector<std::uint64_t> counts(bins, 0);
  for (double s : samples) {
    ASSERT_GE(s, lo) << what;
    ASSERT_LE(s, hi) << what;
    counts[std::min(int((s - lo) / (hi - lo) * bins), bins - 1)]++;
  }
  std::vector<double> p(bins);
  double total = 0.0;
  for (int i = 0; i < bins; ++i) {
    const double a = lo + (hi - lo) * i / bins, b = lo + (hi - lo) * (i + 1) / bins;
    p[i] = simpson(pdf, a, b);
    total += p[i];
  }
  EXPECT_NEAR(total, 1.0, 2e-3) << what << ": the pdf does not integrate to 1";
  int dof = 0;
  const double chi2 = test::chi_square(counts, p, dof);
  std::printf("%s: chi2 %.1f (dof %d, critical %.1f)\n", what, chi2, dof,
              test::chi_square_critical(dof, test::kZ1e3));
  EXPECT_LT(chi2, test::chi_square_critical(dof, test::kZ1e3)) << what;
}

TEST(VolumeMath, HenyeyGreensteinSamplingMatchesItsPdf) {
  for (float g : {-0.7f, 0.0f, 0.3f, 0.9f}) {
    uint rng = rng_init(uvec2(3u), 0u, 101u, 0u);
    const vec3 w = normalize(vec3(0.3f, -0.5f, 0.8f));
    std::vector<double> cosines;
    for (int i = 0; i < 200000; ++i) {
      const vec3 s = hg_sample(w, g, rng_next_vec2(rng));
      ASSERT_NEAR(length(s), 1.0f, 1e-4f);
      cosines.push_back(std::clamp(double(dot(w, s)), -1.0, 1.0));
      // The pdf of the direction is the phase function of its angle.
      ASSERT_NEAR(hg_pdf(w, s, g), hg_phase(dot(w, s), g), 1e-6f * (1.0f + hg_phase(1.0f, g)));
    }
    // Density of cos(theta): 2 pi p(cos theta) (the azimuth integrated out).
    expect_matches_pdf(
        cosines, -1.0, 1.0, 40, [g](double c) { return 2.0 * kPi * hg_phase(float(c), g); },
        ("HG cos theta, g = " + std::to_string(g)).c_str());
  }
}

TEST(VolumeMath, HenyeyGreensteinForwardMeansForward) {
  EXPECT_GT(hg_phase(1.0f, 0.6f), hg_phase(-1.0f, 0.6f));
  EXPECT_NEAR(hg_phase(0.3f, 0.0f), 1.0f / (4.0f * kPi), 1e-7f);
  // Mean cosine of HG is g.
  uint rng = rng_init(uvec2(5u), 0u, 102u, 0u);
  test::RunningStats mean_cos;
  for (int i = 0; i < 100000; ++i) mean_cos.add(hg_sample_cos_theta(0.6f, rng_next_float(rng)));
  EXPECT_NEAR(mean_cos.mean(), 0.6, 4.0 * mean_cos.standard_error());
}

TEST(VolumeMath, ExponentialSamplingMatchesItsPdf) {
  const float sigma = 1.7f;
  uint rng = rng_init(uvec2(7u), 0u, 104u, 0u);
  // Untruncated: samples beyond t_cut go to an overflow check against the survival function.
  const float t_cut = 3.0f;
  std::vector<double> inside;
  std::uint64_t beyond = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const float t = exponential_sample(sigma, rng_next_float(rng));
    ASSERT_GE(t, 0.0f);
    if (t < t_cut)
      inside.push_back(t);
    else
      ++beyond;
  }
  const double survive = exponential_survival(sigma, t_cut);
  const double sd = std::sqrt(n * survive * (1.0 - survive));
  EXPECT_NEAR(double(beyond), n * survive, 4.0 * sd);
  expect_matches_pdf(
      inside, 0.0, t_cut, 30,
      [&](double t) { return exponential_pdf(sigma, float(t)) / (1.0 - survive); }, "exponential");
  EXPECT_EQ(exponential_sample(0.0f, 0.5f), kVolumeNoCollision);
}

TEST(VolumeMath, TruncatedExponentialSamplingMatchesItsPdf) {
  for (float sigma : {0.0f, 1e-7f, 0.4f, 6.0f}) {
    const float t_max = 2.5f;
    uint rng = rng_init(uvec2(9u), 0u, 104u, 0u);
    std::vector<double> samples;
    for (int i = 0; i < 200000; ++i)
      samples.push_back(exponential_sample_truncated(sigma, t_max, rng_next_float(rng)));
    expect_matches_pdf(
        samples, 0.0, t_max, 30,
        [&](double t) { return exponential_pdf_truncated(sigma, t_max, float(t)); },
        ("truncated exponential, sigma = " + std::to_string(sigma)).c_str());
  }
}

TEST(VolumeMath, EquiangularSamplingMatchesItsPdf) {
  struct Case {
    vec3 origin, dir, light;
    float t_min, t_max;
  };
  const Case cases[] = {
      {{0, 0, 0}, {1, 0, 0}, {1.0f, 0.5f, 0.0f}, 0.0f, 4.0f},         // light beside the segment
      {{0, 1, 0}, normalize(vec3(1, -1, 1)), {5, 5, 5}, 0.5f, 3.0f},  // far and off-axis
      {{0, 0, 0}, {0, 0, -1}, {0.0f, 0.05f, -2.0f}, 0.0f, 4.0f},      // close to the line: peaked
  };
  for (const Case& c : cases) {
    uint rng = rng_init(uvec2(11u), 0u, 105u, 0u);
    std::vector<double> samples;
    for (int i = 0; i < 200000; ++i) {
      float pdf = 0.0f;
      const float t =
          equiangular_sample(c.origin, c.dir, c.light, c.t_min, c.t_max, rng_next_float(rng), pdf);
      ASSERT_GT(pdf, 0.0f);
      ASSERT_NEAR(pdf, equiangular_pdf(c.origin, c.dir, c.light, c.t_min, c.t_max, t), 1e-4f * pdf);
      samples.push_back(t);
    }
    expect_matches_pdf(
        samples, c.t_min, c.t_max, 40,
        [&](double t) {
          return equiangular_pdf(c.origin, c.dir, c.light, c.t_min, c.t_max, float(t));
        },
        "equiangular");
  }
}

// The camera-ray scattering distances of single scattering (scatter_distance_sample): the
// exponential technique alone and its one-sample MIS with equiangular, on segments that start
// past the origin (a volume entered part-way along the ray). The samples follow the mixture pdf,
// and the estimator f(t) / pdf(t) of an in-scattering-shaped integrand (transmittance x inverse
// square to the light) is unbiased against Simpson's integral (4 standard errors).
TEST(VolumeMath, ScatterDistanceSamplingMatchesItsPdfAndIsUnbiased) {
  struct Case {
    vec3 origin, dir, light;
    float t0, t1, sigma;
    bool toward_light;
  };
  const Case cases[] = {
      {{0, 0, 0}, {1, 0, 0}, {1.5f, 0.3f, 0.0f}, 0.5f, 4.0f, 0.8f, true},
      {{0, 1, 0}, normalize(vec3(1, -1, 1)), {2, 0, 2}, 1.0f, 6.0f, 2.5f, true},
      {{0, 0, 0}, {0, 0, -1}, {0.0f, 0.1f, -2.0f}, 0.0f, 3.0f, 0.0f, true},
      {{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, 2.0f, 5.0f, 1.2f, false},
  };
  int index = 0;
  for (const Case& c : cases) {
    uint rng = rng_init(uvec2(13u), 0u, 106u, uint(index));
    auto integrand = [&](double t) {
      const vec3 x = c.origin + float(t) * c.dir;
      const vec3 d = x - c.light;
      return std::exp(-1.3 * t) / (double(dot(d, d)) + 0.05);
    };
    std::vector<double> samples;
    double sum = 0.0, sum2 = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      float pdf = 0.0f;
      const vec2 u = rng_next_vec2(rng);
      const float t = scatter_distance_sample(c.origin, c.dir, c.t0, c.t1, c.sigma,
                                              c.toward_light, c.light, u, pdf);
      ASSERT_GT(pdf, 0.0f);
      ASSERT_NEAR(pdf,
                  scatter_distance_pdf(c.origin, c.dir, c.t0, c.t1, c.sigma, c.toward_light,
                                       c.light, t),
                  1e-4f * pdf);
      samples.push_back(t);
      const double w = integrand(t) / pdf;
      sum += w;
      sum2 += w * w;
    }
    const std::string what = "scatter distance, case " + std::to_string(index++);
    expect_matches_pdf(
        samples, c.t0, c.t1, 40,
        [&](double t) {
          return scatter_distance_pdf(c.origin, c.dir, c.t0, c.t1, c.sigma, c.toward_light,
                                      c.light, float(t));
        },
        what.c_str());
    const double mean = sum / n;
    const double se = std::sqrt(std::max(sum2 / n - mean * mean, 0.0) / n);
    const double exact = simpson(integrand, c.t0, c.t1, 20000);
    std::printf("%s: estimate %.6f +- %.6f, exact %.6f\n", what.c_str(), mean, se, exact);
    EXPECT_NEAR(mean, exact, 4.0 * se + 1e-6 * exact) << what;
  }
}

// A homogeneous medium for the tracking estimators (found by argument-dependent lookup).
struct ConstantMedium {
  vec3 sigma_t;
};
vec3 medium_extinction(const ConstantMedium& m, uint, vec3) {
  return m.sigma_t;
}

TEST(VolumeMath, RatioTrackingThroughAConstantBoxMeanAndVariance) {
  const ConstantMedium medium{vec3(0.5f, 1.0f, 2.0f)};
  const float majorant = 3.0f, d = 1.5f;
  const vec3 origin(0.0f), dir(0.0f, 0.0f, 1.0f);
  uint rng = rng_init(uvec2(13u), 0u, 106u, 0u);
  test::RunningStats stats[3];
  const int n = 400000;
  for (int i = 0; i < n; ++i) {
    const vec3 t = ratio_tracking(medium, 0u, origin, dir, 2.0f, 2.0f + d, majorant, 0.0f, rng);
    for (int c = 0; c < 3; ++c) stats[c].add(t[c]);
  }
  for (int c = 0; c < 3; ++c) {
    const double s = medium.sigma_t[c], mu = majorant;
    const double expected = std::exp(-s * d);
    // Tentative collisions are Poisson(mu d) and each multiplies by r = 1 - s / mu, so
    // E[T^k] = exp(-mu d (1 - r^k)).
    const double r = 1.0 - s / mu;
    auto raw = [&](int k) { return std::exp(-mu * d * (1.0 - std::pow(r, k))); };
    const double variance = raw(2) - expected * expected;
    const double m4 = raw(4) - 4 * raw(3) * expected + 6 * raw(2) * expected * expected -
                      3 * std::pow(expected, 4);  // central fourth moment
    const double variance_sd = std::sqrt((m4 - variance * variance) / n);
    std::printf(
        "ratio tracking ch%d: mean %.5f +- %.5f (exp %.5f), var %.5f (closed form %.5f "
        "+- %.5f)\n",
        c, stats[c].mean(), stats[c].standard_error(), expected, stats[c].variance(), variance,
        variance_sd);
    EXPECT_NEAR(stats[c].mean(), expected, 4.0 * stats[c].standard_error());
    EXPECT_NEAR(stats[c].variance(), variance, 5.0 * variance_sd);
  }
}

TEST(VolumeMath, RatioTrackingWithRouletteStaysUnbiased) {
  const ConstantMedium medium{vec3(2.0f, 3.0f, 4.0f)};
  uint rng = rng_init(uvec2(15u), 0u, 107u, 0u);
  test::RunningStats stats[3];
  for (int i = 0; i < 400000; ++i) {
    const vec3 t =
        ratio_tracking(medium, 0u, vec3(0.0f), vec3(1, 0, 0), 0.0f, 1.0f, 5.0f, 0.2f, rng);
    for (int c = 0; c < 3; ++c) stats[c].add(t[c]);
  }
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(stats[c].mean(), std::exp(-double(medium.sigma_t[c])),
                4.0 * stats[c].standard_error());
}

TEST(VolumeMath, ResidualRatioTrackingThroughAConstantBox) {
  const ConstantMedium medium{vec3(0.5f, 1.0f, 2.0f)};
  const float d = 2.0f;
  uint rng = rng_init(uvec2(17u), 0u, 108u, 0u);
  // A control below the medium: the residual is tracked.
  const vec3 control = 0.5f * medium.sigma_t;
  test::RunningStats stats[3];
  for (int i = 0; i < 400000; ++i) {
    const vec3 t = residual_ratio_tracking(medium, 0u, vec3(0.0f), vec3(0, 1, 0), 0.0f, d, control,
                                           1.5f, 0.0f, rng);
    for (int c = 0; c < 3; ++c) stats[c].add(t[c]);
  }
  for (int c = 0; c < 3; ++c) {
    const double expected = std::exp(-double(medium.sigma_t[c]) * d);
    std::printf("residual ratio tracking ch%d: %.5f +- %.5f (exp %.5f)\n", c, stats[c].mean(),
                stats[c].standard_error(), expected);
    EXPECT_NEAR(stats[c].mean(), expected, 4.0 * stats[c].standard_error());
  }
  // The exact control leaves nothing to track: every estimate is exp(-sigma_t d).
  for (int i = 0; i < 100; ++i) {
    const vec3 t = residual_ratio_tracking(medium, 0u, vec3(0.0f), vec3(0, 1, 0), 0.0f, d,
                                           medium.sigma_t, 0.0f, 0.0f, rng);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(t[c], std::exp(-medium.sigma_t[c] * d), 1e-6f);
  }
}

TEST(VolumeMath, EmptySegmentsAndZeroMajorantAreTransparent) {
  const ConstantMedium medium{vec3(1.0f)};
  uint rng = rng_init(uvec2(19u), 0u, 109u, 0u);
  EXPECT_EQ(ratio_tracking(medium, 0u, vec3(0.0f), vec3(1, 0, 0), 1.0f, 1.0f, 2.0f, 0.0f, rng),
            vec3(1.0f));
  EXPECT_EQ(ratio_tracking(ConstantMedium{vec3(0.0f)}, 0u, vec3(0.0f), vec3(1, 0, 0), 0.0f, 5.0f,
                           0.0f, 0.0f, rng),
            vec3(1.0f));
}

// The temporal shift puts a history sample at the point of this frame's ray nearest where its
// medium carried the world point it stood for (the offset is perpendicular to the ray), is
// inverted by volume_shift_back, and has Jacobian a (finite differences); with a still camera,
// a still medium and the same ray it is the identity.
TEST(VolumeMath, TemporalShiftFollowsTheMediumsPointAndItsJacobianIsTheRaysCosine) {
  uint rng = rng_init(uvec2(23u), 0u, 113u, 0u);
  auto random_unit = [&]() {
    return normalize(vec3(rng_next_float(rng), rng_next_float(rng), rng_next_float(rng)) -
                     vec3(0.5f));
  };
  for (int i = 0; i < 1000; ++i) {
    const vec3 prev_origin = 4.0f * random_unit();
    const vec3 origin = prev_origin + 0.3f * random_unit();
    const vec3 prev_dir = random_unit();
    const vec3 dir = normalize(prev_dir + 0.2f * random_unit());
    // Half the cases a still medium, half one that moved and turned a little.
    const mat4 motion = i % 2 == 0 ? mat4(1.0f)
                                   : glm::translate(mat4(1.0f), 0.2f * random_unit()) *
                                         glm::rotate(mat4(1.0f), 0.05f, random_unit());
    const vec2 s = volume_temporal_shift(motion, prev_origin, prev_dir, origin, dir);
    ASSERT_GT(s.x, kVolumeShiftMinCos);
    const float t = 10.0f * rng_next_float(rng);
    const float moved = volume_shift_forward(s, t);
    const vec3 carried = vec3(motion * vec4(prev_origin + t * prev_dir, 1.0f));
    EXPECT_NEAR(dot(origin + moved * dir - carried, dir), 0.0f, 1e-4f) << i;
    EXPECT_NEAR(volume_shift_back(s, moved), t, 1e-4f) << i;
    const float h = 1e-2f;
    const float jacobian =
        (volume_shift_forward(s, t + h) - volume_shift_forward(s, t - h)) / (2 * h);
    EXPECT_NEAR(jacobian, s.x, 1e-3f) << i;
  }
  const vec2 still = volume_temporal_shift(mat4(1.0f), vec3(1, 2, 3), vec3(0, 0, -1),
                                           vec3(1, 2, 3), vec3(0, 0, -1));
  EXPECT_EQ(volume_shift_forward(still, 2.5f), 2.5f);
  EXPECT_EQ(still.x, 1.0f);
}

}  // namespace
}  // namespace lantern::gpu
