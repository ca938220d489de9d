// Helpers shared by the render-graph compile tests: find a pass's barrier on a resource.
#pragma once

#include <optional>
#include <string_view>

#include "runtime/graph/render_graph.h"

namespace lantern::runtime::graph::test {

struct Empty {};

inline constexpr auto kNoExecute = [](PassContext&, const auto&) {};

// Position of pass `name` in the execution order, or nullopt if culled/absent.
inline std::optional<size_t> position(const RenderGraph& g, std::string_view name) {
  const CompiledGraph& c = g.compiled();
  for (size_t i = 0; i < c.passes.size(); ++i)
    if (g.decl().passes[c.passes[i].pass].name == name) return i;
  return std::nullopt;
}

// The barrier on resource `resource` emitted before pass `name`, if any.
inline std::optional<ResourceBarrier> barrier_before(const RenderGraph& g, std::string_view name,
                                                     uint32_t resource) {
  const std::optional<size_t> pos = position(g, name);
  if (!pos) return std::nullopt;
  for (const ResourceBarrier& b : g.compiled().passes[*pos].before.barriers)
    if (b.resource == resource) return b;
  return std::nullopt;
}

}  // namespace lantern::runtime::graph::test
