#include "engine/perf/statistics.h"

#include <gtest/gtest.h>

#include <vector>

namespace lantern::perf {
namespace {

TEST(Statistics, MedianOfOddAndEvenCounts) {
  const std::vector<double> odd = {5.0, 1.0, 3.0};
  const std::vector<double> even = {4.0, 1.0, 3.0, 2.0};
  EXPECT_DOUBLE_EQ(summarize(odd).median, 3.0);
  EXPECT_DOUBLE_EQ(summarize(even).median, 2.5);
}

TEST(Statistics, PercentilesInterpolateBetweenRanks) {
  std::vector<double> v;
  for (int i = 0; i <= 100; ++i) v.push_back(static_cast<double>(100 - i));  // 0..100 reversed
  const Summary s = summarize(v);
  EXPECT_DOUBLE_EQ(s.p95, 95.0);
  EXPECT_DOUBLE_EQ(s.p99, 99.0);
  EXPECT_DOUBLE_EQ(s.max, 100.0);
  EXPECT_DOUBLE_EQ(s.mean, 50.0);
  EXPECT_EQ(s.count, 101u);
  EXPECT_DOUBLE_EQ(percentile(v, 12.5), 12.5);
}

TEST(Statistics, EmptyAndSingleSample) {
  EXPECT_EQ(summarize({}).count, 0u);
  EXPECT_DOUBLE_EQ(summarize({}).median, 0.0);
  const std::vector<double> one = {7.0};
  const Summary s = summarize(one);
  EXPECT_DOUBLE_EQ(s.median, 7.0);
  EXPECT_DOUBLE_EQ(s.p99, 7.0);
}

}  // namespace
}  // namespace lantern::perf
