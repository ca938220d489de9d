// The dependency graph the scheduler derives from system declarations. Within a phase, systems
// A (declared first) and B conflict when one writes a type the other reads or writes, or either
// is exclusive; then B runs after A. Non-conflicting systems may run at the same time. Edges are
// transitively reduced: A→C is dropped when A→B→C already orders them.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "engine/sched/system.h"

namespace lantern {

class SystemGraph {
 public:
  struct Node {
    std::string name;
    Phase phase = Phase::Simulate;
    std::vector<TypeId> reads, writes;  // sorted
    bool exclusive = false;
    std::vector<std::uint32_t> after;   // direct predecessors (reduced), ascending
    std::vector<std::uint32_t> before;  // direct successors (reduced), ascending
  };

  SystemGraph() = default;
  // Validates the declarations (throws RuntimeError naming the system) and derives the graph.
  explicit SystemGraph(const std::deque<SystemDesc>& systems);

  const std::vector<Node>& nodes() const { return nodes_; }
  // Node ids of one phase, in declaration order (which is also a valid execution order).
  const std::vector<std::uint32_t>& phase(Phase p) const { return phases_[static_cast<std::size_t>(p)]; }

  // Node id by name, or -1.
  int find(std::string_view name) const;
  // Direct (reduced) edge a → b.
  bool has_edge(std::string_view a, std::string_view b) const;
  // b must run after a (a path a → ... → b exists, or a's phase precedes b's).
  bool ordered(std::string_view a, std::string_view b) const;
  // Do the declarations of a and b conflict?
  static bool conflicts(const Node& a, const Node& b);

  // Text dump: per phase, each system with its access and predecessors.
  std::string describe() const;

 private:
  bool reaches(std::uint32_t from, std::uint32_t to) const;

  std::vector<Node> nodes_;
  std::array<std::vector<std::uint32_t>, kPhaseCount> phases_;
};

}  // namespace lantern
