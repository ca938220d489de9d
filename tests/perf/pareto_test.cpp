#include "engine/perf/pareto.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lantern::perf {
namespace {

TEST(Pareto, KeepsOnlyUndominatedPointsByIncreasingCost) {
  // (ms, error): a fast+bad, b dominated by c, c slower+better, d slowest+best, e dominated.
  const std::vector<std::pair<double, double>> p = {
      {10, 1.0}, {30, 0.5}, {20, 0.4}, {80, 0.01}, {90, 0.02}};
  EXPECT_EQ(pareto_front(p), (std::vector<std::size_t>{0, 2, 3}));
}

TEST(Pareto, TiesAndBadValues) {
  const std::vector<std::pair<double, double>> p = {
      {10, 1.0}, {10, 0.5}, {5, NAN}, {-1, 0.1}, {20, 0.5}};
  EXPECT_EQ(pareto_front(p), (std::vector<std::size_t>{1}));  // equal cost, lower error wins
  EXPECT_TRUE(pareto_front({}).empty());
}

}  // namespace
}  // namespace lantern::perf
