// Validation and derivation of the system dependency graph (see system_graph.h).
#include "engine/sched/system_graph.h"

#include <algorithm>
#include <unordered_set>

#include <fmt/format.h>

#include "engine/core/error.h"

namespace lantern {
namespace {

// Sorted type ids of a declaration list; a type listed twice is a mistake in the declaration.
std::vector<TypeId> sorted_types(const SystemDesc& s, const std::vector<Access>& list, const char* what) {
  std::vector<TypeId> ids;
  ids.reserve(list.size());
  for (const Access& a : list) ids.push_back(a.type);
  std::sort(ids.begin(), ids.end());
  const auto dup = std::adjacent_find(ids.begin(), ids.end());
  if (dup != ids.end()) {
    throw RuntimeError(fmt::format("scheduler: system '{}' declares {} {} twice", s.name, what, type_name(*dup)));
  }
  return ids;
}

bool intersects(const std::vector<TypeId>& a, const std::vector<TypeId>& b) {
  auto i = a.begin();
  auto j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (*i == *j) return true;
    (*i < *j) ? ++i : ++j;
  }
  return false;
}

// Step 1: every declaration is well formed on its own, and names are unique.
void validate(const std::deque<SystemDesc>& systems) {
  std::unordered_set<std::string_view> names;
  for (std::size_t i = 0; i < systems.size(); ++i) {
    const SystemDesc& s = systems[i];
    if (s.name.empty()) throw RuntimeError(fmt::format("scheduler: system #{} has no name", i));
    if (!names.insert(s.name).second) {
      throw RuntimeError(fmt::format("scheduler: two systems are named '{}'; names must be unique", s.name));
    }
    if (static_cast<std::size_t>(s.phase) >= kPhaseCount) {
      throw RuntimeError(fmt::format("scheduler: system '{}' has an invalid phase", s.name));
    }
    if (!s.fn) throw RuntimeError(fmt::format("scheduler: system '{}' has no function (call .run(fn))", s.name));
    if (s.reads.empty() && s.writes.empty() && !s.exclusive) {
      throw RuntimeError(fmt::format(
          "scheduler: system '{}' declares no reads or writes; declare its access or mark it .exclusive()", s.name));
    }
  }
}

}  // namespace

bool SystemGraph::conflicts(const Node& a, const Node& b) {
  return a.exclusive || b.exclusive || intersects(a.writes, b.writes) || intersects(a.writes, b.reads) ||
         intersects(b.writes, a.reads);
}

SystemGraph::SystemGraph(const std::deque<SystemDesc>& systems) {
  validate(systems);

  // Step 2: nodes with sorted access sets; a type both read and written is declared wrongly.
  nodes_.reserve(systems.size());
  for (const SystemDesc& s : systems) {
    Node n{s.name, s.phase, sorted_types(s, s.reads, "read of"), sorted_types(s, s.writes, "write of"), s.exclusive, {}, {}};
    std::vector<TypeId> both;
    std::set_intersection(n.reads.begin(), n.reads.end(), n.writes.begin(), n.writes.end(), std::back_inserter(both));
    if (!both.empty()) {
      throw RuntimeError(fmt::format("scheduler: system '{}' declares {} as both read and written; declare it once, as a write",
                                     s.name, type_name(both.front())));
    }
    phases_[static_cast<std::size_t>(s.phase)].push_back(static_cast<std::uint32_t>(nodes_.size()));
    nodes_.push_back(std::move(n));
  }

  // Step 3: per phase, order conflicting pairs by declaration order, keeping only edges that are
  // not implied by a path through an intermediate system (transitive reduction). Visiting
  // predecessors nearest-first, an edge i→j is implied iff i is already an ancestor of j.
  const std::size_t n = nodes_.size();
  std::vector<std::vector<bool>> ancestor(n, std::vector<bool>(n, false));
  for (const auto& ids : phases_) {
    for (std::size_t pj = 0; pj < ids.size(); ++pj) {
      const std::uint32_t j = ids[pj];
      for (std::size_t pi = pj; pi-- > 0;) {
        const std::uint32_t i = ids[pi];
        if (ancestor[j][i] || !conflicts(nodes_[i], nodes_[j])) continue;
        nodes_[j].after.push_back(i);
        nodes_[i].before.push_back(j);
        ancestor[j][i] = true;
        for (std::size_t k = 0; k < n; ++k) {
          if (ancestor[i][k]) ancestor[j][k] = true;
        }
      }
    }
  }
  for (Node& node : nodes_) {
    std::sort(node.after.begin(), node.after.end());
    std::sort(node.before.begin(), node.before.end());
  }
}

int SystemGraph::find(std::string_view name) const {
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

bool SystemGraph::has_edge(std::string_view a, std::string_view b) const {
  const int ia = find(a);
  const int ib = find(b);
  if (ia < 0 || ib < 0) return false;
  const auto& after = nodes_[static_cast<std::size_t>(ib)].after;
  return std::find(after.begin(), after.end(), static_cast<std::uint32_t>(ia)) != after.end();
}

bool SystemGraph::reaches(std::uint32_t from, std::uint32_t to) const {
  if (from == to) return true;
  for (std::uint32_t next : nodes_[from].before) {
    if (next <= to && reaches(next, to)) return true;  // edges go forward in declaration order
  }
  return false;
}

bool SystemGraph::ordered(std::string_view a, std::string_view b) const {
  const int ia = find(a);
  const int ib = find(b);
  if (ia < 0 || ib < 0 || ia == ib) return false;
  const Node& na = nodes_[static_cast<std::size_t>(ia)];
  const Node& nb = nodes_[static_cast<std::size_t>(ib)];
  if (na.phase != nb.phase) return na.phase < nb.phase;
  return reaches(static_cast<std::uint32_t>(ia), static_cast<std::uint32_t>(ib));
}

std::string SystemGraph::describe() const {
  const auto names = [](const std::vector<TypeId>& ids) {
    std::string out;
    for (TypeId id : ids) out += fmt::format("{}{}", out.empty() ? "" : ", ", type_name(id));
    return out.empty() ? std::string("-") : out;
  };
  std::string out;
  for (std::size_t p = 0; p < kPhaseCount; ++p) {
    if (phases_[p].empty()) continue;
    out += fmt::format("phase {}\n", phase_name(static_cast<Phase>(p)));
    for (std::uint32_t id : phases_[p]) {
      const Node& node = nodes_[id];
      std::string after;
      for (std::uint32_t a : node.after) after += fmt::format("{}{}", after.empty() ? "" : ", ", nodes_[a].name);
      out += fmt::format("  {}{}\n    reads: {}\n    writes: {}\n    after: {}\n", node.name,
                         node.exclusive ? " (exclusive)" : "", names(node.reads), names(node.writes),
                         after.empty() ? "-" : after);
    }
  }
  return out;
}

}  // namespace lantern
