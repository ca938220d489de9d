// RenderGraph::dump(): the compiled frame as text — passes in order with their barriers and
// uses, culled passes, resources with lifetimes and memory placement, the memory saved.
#include <fmt/format.h>

#include "runtime/graph/render_graph.h"

namespace lantern::runtime::graph {

namespace {

std::string describe(const ResourceDecl& r) {
  if (!r.is_image) return fmt::format("buffer {} B", r.buffer.size);
  return fmt::format("image {}x{}x{} format {} mips {} layers {}", r.image.extent.width,
                     r.image.extent.height, r.image.extent.depth, static_cast<int>(r.image.format),
                     r.image.mip_levels, r.image.array_layers);
}

std::string scope(const AccessState& s, bool image) {
  std::string text = fmt::format("{}/{}", stage_names(s.stages), access_names(s.access));
  if (image) text += fmt::format(" [{}]", layout_name(s.layout));
  return text;
}

void dump_barriers(std::string& out, const GraphDecl& d, const BarrierBatch& batch) {
  for (const ResourceBarrier& b : batch.barriers) {
    const ResourceDecl& r = d.resources[b.resource];
    out += fmt::format("      barrier {}{}: {} -> {}\n", r.name, b.aliasing ? " (aliasing)" : "",
                       scope(b.src, r.is_image), scope(b.dst, r.is_image));
  }
}

}  // namespace

std::string RenderGraph::dump() const {
  const GraphDecl& d = decl_;
  const CompiledGraph& c = compiled_;
  if (!compiled_this_frame_) return "render graph: not baked\n";
  std::string out =
      fmt::format("render graph, frame {}: {} passes ({} culled), {} resources, {} barriers\n",
                  frame(), c.passes.size(), c.culled.size(), d.resources.size(), c.barrier_count());
  out += "passes:\n";
  for (size_t pos = 0; pos < c.passes.size(); ++pos) {
    const PassDecl& pass = d.passes[c.passes[pos].pass];
    out += fmt::format("  [{}] {} ({}{})\n", pos, pass.name, pass_kind_name(pass.kind),
                       pass.side_effect ? ", side effect" : "");
    dump_barriers(out, d, c.passes[pos].before);
    for (const ResourceUse& u : pass.uses)
      out += fmt::format("      {} {} v{}{} as {}\n", is_write(u.access) ? "write" : "read ",
                         d.resources[u.resource].name, u.version,
                         is_write(u.access) ? fmt::format("->v{}", u.version + 1) : "",
                         access_name(u.access));
  }
  if (!c.after.empty()) {
    out += "  end of frame:\n";
    dump_barriers(out, d, c.after);
  }
  for (uint32_t p : c.culled) out += fmt::format("  culled: {}\n", d.passes[p].name);
  out += "resources:\n";
  for (uint32_t r = 0; r < d.resources.size(); ++r) {
    const ResourceDecl& res = d.resources[r];
    const Lifetime& l = c.lifetimes[r];
    std::string where;
    if (res.origin == Origin::Transient && l.used())
      where = fmt::format(", memory offset {}", c.memory_offset(r));
    else if (res.origin == Origin::History || res.origin == Origin::HistoryPrevious)
      where = fmt::format(", slot {}", res.history_slot);
    out += fmt::format("  {} {} ({}), {}{}\n", res.name, describe(res), origin_name(res.origin),
                       l.used() ? fmt::format("passes {}..{}", l.first, l.last) : "unused", where);
  }
  out += fmt::format("transient memory: {} B aliased ({} B without aliasing, {} B saved)\n",
                     c.alias_plan.block_size, c.alias_plan.unaliased_size, c.alias_plan.saved());
  return out;
}

}  // namespace lantern::runtime::graph
