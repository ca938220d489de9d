// The Pareto front of (cost, error) points: those no other point beats in both (lower cost and
// lower error, or equal in one and lower in the other). What `lantern trade` marks.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace lantern::perf {

// Indices of the points on the front, ordered by increasing cost. Points with a non-finite or
// negative coordinate are never on it.
std::vector<std::size_t> pareto_front(const std::vector<std::pair<double, double>>& cost_error);

}  // namespace lantern::perf
