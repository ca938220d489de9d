// Small statistics helpers for the shared-math tests: running mean/standard error and the
// chi-square goodness-of-fit statistic with its critical value.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace lantern::test {

// Welford's running mean and variance, in double.
class RunningStats {
 public:
  void add(double x) {
    ++count_;
    double delta = x - mean_;
    mean_ += delta / static_cast<double>(count_);
    m2_ += delta * (x - mean_);
  }
  double mean() const { return mean_; }
  double variance() const { return count_ > 1 ? m2_ / static_cast<double>(count_ - 1) : 0.0; }
  // Standard error of the mean (the sigma of the estimate).
  double standard_error() const { return std::sqrt(variance() / static_cast<double>(count_)); }
  std::uint64_t count() const { return count_; }

 private:
  std::uint64_t count_ = 0;
  double mean_ = 0.0;
  double m2_ = 0.0;
};

// Pearson's chi-square statistic of observed counts against expected probabilities (bins with
// probability 0 are excluded: the caller checks they stayed empty). Returns the statistic and
// sets dof to (non-empty bins - 1).
inline double chi_square(const std::vector<std::uint64_t>& observed,
                         const std::vector<double>& probability, int& dof) {
  std::uint64_t total = 0;
  for (std::uint64_t o : observed) total += o;
  double chi2 = 0.0;
  dof = -1;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    if (probability[i] <= 0.0) continue;
    double expected = probability[i] * static_cast<double>(total);
    double d = static_cast<double>(observed[i]) - expected;
    chi2 += d * d / expected;
    ++dof;
  }
  return chi2;
}

// Upper critical value of the chi-square distribution with `dof` degrees of freedom at the
// standard-normal quantile z (Wilson-Hilferty approximation, accurate to ~1% for dof >= 3).
// z = 3.0902 is the p = 1e-3 threshold used throughout these tests.
inline double chi_square_critical(int dof, double z) {
  double k = static_cast<double>(dof);
  double a = 2.0 / (9.0 * k);
  double c = 1.0 - a + z * std::sqrt(a);
  return k * c * c * c;
}

inline constexpr double kZ1e3 = 3.0902;  // one-sided p = 1e-3

}  // namespace lantern::test
