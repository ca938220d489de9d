#include "engine/perf/pareto.h"

#include <algorithm>
#include <cmath>

namespace lantern::perf {

std::vector<std::size_t> pareto_front(const std::vector<std::pair<double, double>>& points) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto [c, e] = points[i];
    if (std::isfinite(c) && std::isfinite(e) && c >= 0.0 && e >= 0.0) order.push_back(i);
  }
  // By cost, then error: walking in that order, a point is on the front when its error is lower
  // than every cheaper (or equally cheap, lower-error) point's.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return points[a] < points[b];
  });
  std::vector<std::size_t> front;
  double best_error = INFINITY;
  for (std::size_t i : order) {
    if (points[i].second < best_error) {
      front.push_back(i);
      best_error = points[i].second;
    }
  }
  return front;
}

}  // namespace lantern::perf
