// The render-graph compiler. Each step is a small function; compile_graph() runs them in order.
#include "runtime/graph/graph_compiler.h"

#include <fmt/format.h>

#include <algorithm>
#include <queue>
#include <set>

#include "runtime/gpu/image.h"

namespace lantern::runtime::graph {

namespace {

constexpr VkAccessFlags2 kWriteAccess =
    VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
    VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_WRITE_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT |
    VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;

// One pass's combined use of one resource (a pass may declare several accesses to it).
struct MergedUse {
  uint32_t resource = kInvalidIndex;
  AccessState state;
  bool writes = false;
};

using Errors = std::vector<std::string>;

std::string pass_label(const GraphDecl& d, uint32_t pass) {
  return fmt::format("pass '{}'", d.passes[pass].name);
}

// Step 1 — validate each declared use: access kind fits the resource, a read has contents to
// read, a pass does not mix image layouts on one resource.
void validate_uses(const GraphDecl& d, Errors& errors) {
  for (uint32_t p = 0; p < d.passes.size(); ++p) {
    const PassDecl& pass = d.passes[p];
    for (const ResourceUse& use : pass.uses) {
      const ResourceDecl& r = d.resources[use.resource];
      if (pass.kind == PassKind::Transfer && use.access != Access::TransferSrc &&
          use.access != Access::TransferDst)
        errors.push_back(fmt::format("{} is a transfer pass but uses '{}' as {}", pass_label(d, p),
                                     r.name, access_name(use.access)));
      if ((pass.kind == PassKind::Host) != (use.access == Access::HostReadWrite))
        errors.push_back(fmt::format("{} is a {} pass but uses '{}' as {} (host passes, and only "
                                     "they, use host-read-write)",
                                     pass_label(d, p), pass_kind_name(pass.kind), r.name,
                                     access_name(use.access)));
      if (use.access == Access::HostReadWrite && r.origin != Origin::Imported)
        errors.push_back(fmt::format("{} uses '{}' on the host, which only an imported "
                                     "(host-visible, mapped) buffer allows",
                                     pass_label(d, p), r.name));
      if (is_read(use.access) && use.version == 0 && !r.has_initial_contents())
        errors.push_back(fmt::format("{} reads '{}' ({}) before any pass wrote it",
                                     pass_label(d, p), r.name, access_name(use.access)));
    }
  }
}

// Step 2 — dependency edges between passes, from versions: writer(v) → readers(v) (read after
// write), readers(v) → writer(v+1) (write after read), writer(v) → writer(v+1) (write after write).
std::vector<std::set<uint32_t>> build_edges(const GraphDecl& d, Errors& errors) {
  std::vector<std::set<uint32_t>> edges(d.passes.size());
  for (uint32_t p = 0; p < d.passes.size(); ++p) {
    for (const ResourceUse& use : d.passes[p].uses) {
      const ResourceDecl& r = d.resources[use.resource];
      const uint32_t producer = use.version > 0 ? r.writers[use.version - 1] : kInvalidIndex;
      const uint32_t next_writer =
          use.version < r.latest_version ? r.writers[use.version] : kInvalidIndex;
      if (is_write(use.access)) {
        if (producer != kInvalidIndex && producer != p) edges[producer].insert(p);
        continue;
      }
      if (producer == p)
        errors.push_back(fmt::format("{} reads '{}' version {} which it writes itself (cycle)",
                                     pass_label(d, p), r.name, use.version));
      else if (producer != kInvalidIndex)
        edges[producer].insert(p);
      if (next_writer != kInvalidIndex && next_writer != p) edges[p].insert(next_writer);
    }
  }
  return edges;
}

// Step 3 — cull: walking back from the last pass, a pass lives if it has a side effect, writes
// something that outlives the frame (imported, history), or writes a version a live pass reads.
std::vector<bool> find_live_passes(const GraphDecl& d) {
  std::vector<bool> live(d.passes.size(), false);
  // readers_alive[resource][version]: some live pass reads that version.
  std::vector<std::vector<bool>> read_live(d.resources.size());
  for (uint32_t r = 0; r < d.resources.size(); ++r)
    read_live[r].assign(d.resources[r].latest_version + 1, false);
  for (uint32_t p = static_cast<uint32_t>(d.passes.size()); p-- > 0;) {
    const PassDecl& pass = d.passes[p];
    bool alive = pass.side_effect;
    for (const ResourceUse& use : pass.uses) {
      if (!is_write(use.access)) continue;
      const ResourceDecl& r = d.resources[use.resource];
      const bool outlives_frame = r.origin != Origin::Transient;
      if (outlives_frame || read_live[use.resource][use.version + 1]) alive = true;
    }
    live[p] = alive;
    if (!alive) continue;
    for (const ResourceUse& use : pass.uses)
      if (is_read(use.access)) read_live[use.resource][use.version] = true;
  }
  return live;
}

// Step 4 — order: topological over live passes, ties broken by declaration order, so a graph
// declared in a valid order runs exactly in that order. Leftover passes form a cycle.
std::vector<uint32_t> order_passes(const GraphDecl& d, const std::vector<std::set<uint32_t>>& edges,
                                   const std::vector<bool>& live, Errors& errors) {
  std::vector<uint32_t> indegree(d.passes.size(), 0);
  for (uint32_t p = 0; p < d.passes.size(); ++p)
    if (live[p])
      for (uint32_t q : edges[p])
        if (live[q]) ++indegree[q];
  std::priority_queue<uint32_t, std::vector<uint32_t>, std::greater<>> ready;
  for (uint32_t p = 0; p < d.passes.size(); ++p)
    if (live[p] && indegree[p] == 0) ready.push(p);
  std::vector<uint32_t> order;
  while (!ready.empty()) {
    const uint32_t p = ready.top();
    ready.pop();
    order.push_back(p);
    for (uint32_t q : edges[p])
      if (live[q] && --indegree[q] == 0) ready.push(q);
  }
  const size_t live_count = static_cast<size_t>(std::count(live.begin(), live.end(), true));
  if (order.size() != live_count) {
    std::string names;
    for (uint32_t p = 0; p < d.passes.size(); ++p)
      if (live[p] && indegree[p] > 0)
        names += fmt::format("{}'{}'", names.empty() ? "" : ", ", d.passes[p].name);
    errors.push_back(fmt::format(
        "dependency cycle between passes {} (a pass reads a version that a pass it must "
        "precede overwrites)",
        names));
  }
  return order;
}

// Combine one pass's uses per resource; a resource may have one image layout per pass.
std::vector<MergedUse> merge_uses(const GraphDecl& d, uint32_t p, Errors& errors) {
  std::vector<MergedUse> merged;
  for (const ResourceUse& use : d.passes[p].uses) {
    const ResourceDecl& r = d.resources[use.resource];
    const AccessState s = access_state(use.access, d.passes[p].kind, r.is_image);
    auto it = std::find_if(merged.begin(), merged.end(),
                           [&](const MergedUse& m) { return m.resource == use.resource; });
    if (it == merged.end()) {
      merged.push_back({use.resource, s, is_write(use.access)});
      continue;
    }
    if (r.is_image && it->state.layout != s.layout)
      errors.push_back(fmt::format("{} uses image '{}' in two layouts ({} and {})",
                                   pass_label(d, p), r.name, layout_name(it->state.layout),
                                   layout_name(s.layout)));
    it->state.stages |= s.stages;
    it->state.access |= s.access;
    it->writes = it->writes || is_write(use.access);
  }
  return merged;
}

// Step 5 — lifetimes: first and last position in the execution order that touches a resource.
std::vector<Lifetime> compute_lifetimes(const GraphDecl& d, const std::vector<uint32_t>& order) {
  std::vector<Lifetime> lifetimes(d.resources.size());
  for (uint32_t pos = 0; pos < order.size(); ++pos)
    for (const ResourceUse& use : d.passes[order[pos]].uses) {
      Lifetime& l = lifetimes[use.resource];
      if (!l.used()) l.first = pos;
      l.last = pos;
    }
  return lifetimes;
}

// Step 6 — aliasing: transients whose lifetimes do not overlap share memory.
void plan_memory(const GraphDecl& d, const CompileOptions& options, CompiledGraph& out) {
  for (uint32_t r = 0; r < d.resources.size(); ++r) {
    if (d.resources[r].origin != Origin::Transient || !out.lifetimes[r].used()) continue;
    const MemoryRequirement m = options.memory_requirement
                                    ? options.memory_requirement(d.resources[r])
                                    : estimate_memory(d.resources[r]);
    out.aliased.push_back(r);
    out.alias_requests.push_back(
        {m.size, m.alignment, out.lifetimes[r].first, out.lifetimes[r].last});
  }
  out.alias_plan = plan_aliasing(out.alias_requests);
}

// Synchronisation state of one resource while walking the execution order.
struct SyncState {
  VkPipelineStageFlags2 write_stages = 0;  // last write (or layout transition) to wait for
  VkAccessFlags2 write_access = 0;
  VkPipelineStageFlags2 read_stages = 0;     // reads since that write (write-after-read waits)
  VkPipelineStageFlags2 visible_stages = 0;  // scopes the last write is already visible to
  VkAccessFlags2 visible_access = 0;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;

  static SyncState from(const AccessState& s) {
    SyncState state;
    state.layout = s.layout;
    if ((s.access & kWriteAccess) != 0) {
      state.write_stages = s.stages;
      state.write_access = s.access & kWriteAccess;
    } else {
      state.read_stages = s.stages;
    }
    return state;
  }
  [[nodiscard]] AccessState summary() const {
    return {write_stages | read_stages | visible_stages, write_access, layout};
  }
};

// The barrier (if any) that must precede `use` of a resource in `state`; updates `state`.
std::optional<ResourceBarrier> derive_barrier(SyncState& state, const AccessState& use, bool writes,
                                              bool is_image) {
  const AccessState old{state.write_stages | state.read_stages | state.visible_stages,
                        state.write_access, state.layout};
  const bool transition = is_image && use.layout != state.layout;
  std::optional<ResourceBarrier> barrier;
  if (transition || writes) {
    // Layout transitions and writes wait for every earlier access; earlier writes are made
    // available (write after write), earlier reads need only an execution dependency.
    if (transition || old.stages != 0 || old.access != 0)
      barrier = ResourceBarrier{kInvalidIndex, old, use, false};
    // A read-only transition: the barrier made the earlier write available, so what later uses
    // wait for is the transition (its stages), with no write access of its own. (Keeping the old
    // write's access here paired it with the transition's stages: a second transition then
    // waited for COLOR_ATTACHMENT_WRITE at COMPUTE_SHADER, VUID-VkImageMemoryBarrier2-03911.)
    state.write_stages = use.stages;
    state.write_access = writes ? (use.access & kWriteAccess) : 0;
    state.read_stages = writes ? 0 : use.stages;
    state.visible_stages = writes ? 0 : use.stages;
    state.visible_access = writes ? 0 : use.access;
    state.layout = is_image ? use.layout : state.layout;
    return barrier;
  }
  // Read in the current layout: wait for the last write unless already visible to this scope.
  const bool written = state.write_stages != 0 || state.write_access != 0;
  const bool visible =
      (use.stages & ~state.visible_stages) == 0 && (use.access & ~state.visible_access) == 0;
  if (written && !visible) {
    barrier = ResourceBarrier{
        kInvalidIndex,
        {state.write_stages | state.visible_stages, state.write_access, state.layout},
        use,
        false};
    state.visible_stages |= use.stages;
    state.visible_access |= use.access;
  }
  state.read_stages |= use.stages;
  return barrier;
}

// Step 7 — barriers: walk the order keeping each resource's sync state; the first use of
// aliased memory also waits for the transients that used those bytes before.
void derive_barriers(const GraphDecl& d, const std::vector<uint32_t>& order, CompiledGraph& out,
                     Errors& errors) {
  std::vector<SyncState> states(d.resources.size());
  for (uint32_t r = 0; r < d.resources.size(); ++r)
    if (d.resources[r].origin != Origin::Transient)
      states[r] = SyncState::from(d.resources[r].import.initial);

  // Aliasing predecessors: earlier transients whose bytes overlap (lifetimes end before).
  std::vector<std::vector<uint32_t>> predecessors(d.resources.size());
  for (size_t a = 0; a < out.aliased.size(); ++a)
    for (size_t b = 0; b < out.aliased.size(); ++b)
      if (out.alias_requests[b].last_pass < out.alias_requests[a].first_pass &&
          memory_overlaps(out.alias_plan, out.alias_requests, a, b))
        predecessors[out.aliased[a]].push_back(out.aliased[b]);
  std::vector<AccessState> used_scope(d.resources.size());  // all scopes a transient was used in

  for (uint32_t pos = 0; pos < order.size(); ++pos) {
    CompiledPass compiled{order[pos], {}};
    for (const MergedUse& use : merge_uses(d, order[pos], errors)) {
      const ResourceDecl& r = d.resources[use.resource];
      std::optional<ResourceBarrier> barrier =
          derive_barrier(states[use.resource], use.state, use.writes, r.is_image);
      const bool first_use = out.lifetimes[use.resource].first == pos;
      if (first_use && !predecessors[use.resource].empty()) {
        if (!barrier) barrier = ResourceBarrier{kInvalidIndex, {}, use.state, false};
        for (uint32_t previous : predecessors[use.resource]) {
          barrier->src.stages |= used_scope[previous].stages;
          barrier->src.access |= used_scope[previous].access & kWriteAccess;
        }
        barrier->aliasing = true;
      }
      used_scope[use.resource].stages |= use.state.stages;
      used_scope[use.resource].access |= use.state.access;
      if (barrier) {
        barrier->resource = use.resource;
        compiled.before.barriers.push_back(*barrier);
      }
    }
    out.passes.push_back(std::move(compiled));
  }

  // Step 8 — final transitions of imported resources that ask for one, then final states.
  for (uint32_t r = 0; r < d.resources.size(); ++r) {
    const ResourceDecl& res = d.resources[r];
    if (res.origin == Origin::Imported && res.import.final) {
      const AccessState& f = *res.import.final;
      const bool writes = (f.access & kWriteAccess) != 0;
      if (auto barrier = derive_barrier(states[r], f, writes, res.is_image)) {
        barrier->resource = r;
        out.after.barriers.push_back(*barrier);
      }
    }
    out.final_states.push_back(states[r].summary());
  }
}

std::string join_errors(const Errors& errors) {
  std::string text = fmt::format("render graph: {} error(s):", errors.size());
  for (const std::string& e : errors) text += "\n  " + e;
  return text;
}


}  // namespace

MemoryRequirement estimate_memory(const ResourceDecl& r) {
  if (!r.is_image) return {r.buffer.size, 256};
  const ImageDesc& i = r.image;
  uint64_t bytes = 0;
  for (uint32_t mip = 0; mip < i.mip_levels; ++mip)
    bytes += uint64_t{std::max(1u, i.extent.width >> mip)} * std::max(1u, i.extent.height >> mip) *
             std::max(1u, i.extent.depth >> mip);
  return {bytes * texel_size(i.format) * i.array_layers, 4096};
}

size_t CompiledGraph::barrier_count() const {
  size_t count = after.barriers.size();
  for (const CompiledPass& p : passes) count += p.before.barriers.size();
  return count;
}

uint64_t CompiledGraph::memory_offset(uint32_t resource) const {
  for (size_t i = 0; i < aliased.size(); ++i)
    if (aliased[i] == resource) return alias_plan.offsets[i];
  return ~uint64_t{0};
}

CompiledGraph compile_graph(const GraphDecl& decl, const CompileOptions& options) {
  Errors errors = decl.errors;
  validate_uses(decl, errors);
  const std::vector<std::set<uint32_t>> edges = build_edges(decl, errors);
  const std::vector<bool> live = find_live_passes(decl);
  const std::vector<uint32_t> order = order_passes(decl, edges, live, errors);
  if (!errors.empty()) throw RenderGraphError(join_errors(errors));

  CompiledGraph out;
  for (uint32_t p = 0; p < decl.passes.size(); ++p)
    if (!live[p]) out.culled.push_back(p);
  out.lifetimes = compute_lifetimes(decl, order);
  plan_memory(decl, options, out);
  derive_barriers(decl, order, out, errors);
  if (!errors.empty()) throw RenderGraphError(join_errors(errors));
  return out;
}

}  // namespace lantern::runtime::graph
