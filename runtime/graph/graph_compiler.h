// compile_graph(): GraphDecl → CompiledGraph in small steps (validate, cull, order, lifetimes,
// aliasing, barriers). Throws RenderGraphError listing every problem found.
#pragma once

#include <functional>

#include "engine/core/error.h"
#include "runtime/graph/compiled_graph.h"
#include "runtime/graph/graph_decl.h"

namespace lantern::runtime::graph {

class RenderGraphError : public RuntimeError {
 public:
  using RuntimeError::RuntimeError;
};

struct CompileOptions {
  // Memory needs of a transient; without a device an estimate from its description is used.
  std::function<MemoryRequirement(const ResourceDecl&)> memory_requirement;
};

[[nodiscard]] MemoryRequirement estimate_memory(const ResourceDecl& resource);

[[nodiscard]] CompiledGraph compile_graph(const GraphDecl& decl,
                                          const CompileOptions& options = {});

}  // namespace lantern::runtime::graph
