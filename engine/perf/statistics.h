// Summary statistics of timing samples (frame ms, pass ms): median and nearest-rank
// percentiles, the figures `lantern bench` reports and budgets are checked against.
#pragma once

#include <span>

namespace lantern::perf {

struct Summary {
  double median = 0.0;
  double p95 = 0.0;
  double p99 = 0.0;
  double max = 0.0;
  double mean = 0.0;
  std::size_t count = 0;
};

// Percentile q in [0, 100] by linear interpolation between closest ranks (q = 50: the median).
// 0 for no samples.
double percentile(std::span<const double> samples, double q);

Summary summarize(std::span<const double> samples);

}  // namespace lantern::perf
