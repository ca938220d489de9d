// The result of compiling a GraphDecl: execution order, the barriers before each pass and at the
// end of the frame, resource lifetimes and the transient memory plan. Pure data.
#pragma once

#include <cstdint>
#include <vector>

#include "runtime/graph/alias_planner.h"
#include "runtime/graph/handles.h"
#include "runtime/graph/resource_desc.h"

namespace lantern::runtime::graph {

struct ResourceBarrier {
  uint32_t resource = kInvalidIndex;
  AccessState src;        // src.layout = old layout (images)
  AccessState dst;        // dst.layout = new layout (images)
  bool aliasing = false;  // first use of bytes another transient used earlier this frame
};

struct BarrierBatch {
  std::vector<ResourceBarrier> barriers;
  [[nodiscard]] bool empty() const { return barriers.empty(); }
};

struct CompiledPass {
  uint32_t pass = kInvalidIndex;  // index into GraphDecl::passes
  BarrierBatch before;
};

struct Lifetime {
  uint32_t first = kInvalidIndex;  // position in CompiledGraph::passes; invalid = unused
  uint32_t last = kInvalidIndex;
  [[nodiscard]] bool used() const { return first != kInvalidIndex; }
};

struct MemoryRequirement {
  uint64_t size = 0;
  uint64_t alignment = 1;
};

struct CompiledGraph {
  std::vector<CompiledPass> passes;       // execution order
  std::vector<uint32_t> culled;           // pass indices removed (nobody reads their outputs)
  BarrierBatch after;                     // final transitions of imported resources
  std::vector<Lifetime> lifetimes;        // per resource
  std::vector<AccessState> final_states;  // per resource, after the frame
  std::vector<uint32_t> aliased;          // transient resource indices, in plan order
  std::vector<AliasRequest> alias_requests;
  AliasPlan alias_plan;  // offsets parallel to `aliased`

  [[nodiscard]] size_t barrier_count() const;
  // Offset of a transient in the shared block, or kInvalidIndex-as-uint64 if not placed.
  [[nodiscard]] uint64_t memory_offset(uint32_t resource) const;
};

}  // namespace lantern::runtime::graph
