// RenderGraph declarations (resources, passes, history) and the per-frame bake/commit cycle.
#include "runtime/graph/render_graph.h"

#include <fmt/format.h>

namespace lantern::runtime::graph {

const char* origin_name(Origin origin) {
  switch (origin) {
    case Origin::Transient:
      return "transient";
    case Origin::Imported:
      return "imported";
    case Origin::History:
      return "history";
    case Origin::HistoryPrevious:
      return "history-previous";
  }
  return "?";
}

// ---- PassBuilder ----

bool PassBuilder::check(uint32_t resource, Access access, bool image) {
  GraphDecl& d = graph_.decl_;
  const std::string& pass = d.passes[pass_].name;
  if (resource >= d.resources.size()) {
    d.errors.push_back(
        fmt::format("pass '{}' uses an invalid handle (no history this frame?)", pass));
    return false;
  }
  const ResourceDecl& r = d.resources[resource];
  if (r.is_image != image) {
    d.errors.push_back(
        fmt::format("pass '{}' uses '{}' through the wrong handle type", pass, r.name));
    return false;
  }
  if (image ? !allowed_on_image(access) : !allowed_on_buffer(access)) {
    d.errors.push_back(fmt::format("pass '{}' uses {} '{}' as {}, which applies only to {}s", pass,
                                   image ? "image" : "buffer", r.name, access_name(access),
                                   image ? "buffer" : "image"));
    return false;
  }
  return true;
}

void PassBuilder::declare_read(uint32_t resource, uint32_t version, Access access, bool image) {
  if (!check(resource, access, image)) return;
  GraphDecl& d = graph_.decl_;
  ResourceDecl& r = d.resources[resource];
  if (is_write(access)) {
    d.errors.push_back(fmt::format("pass '{}' declares {} of '{}' as a read; use write()",
                                   d.passes[pass_].name, access_name(access), r.name));
    return;
  }
  if (version > r.latest_version) {
    d.errors.push_back(fmt::format("pass '{}' reads '{}' version {} that does not exist",
                                   d.passes[pass_].name, r.name, version));
    return;
  }
  r.buffer_usage |= buffer_usage(access);
  r.image_usage |= image_usage(access);
  d.passes[pass_].uses.push_back({resource, version, access});
}

uint32_t PassBuilder::declare_write(uint32_t resource, uint32_t version, Access access,
                                    bool image) {
  if (!check(resource, access, image)) return version;
  GraphDecl& d = graph_.decl_;
  ResourceDecl& r = d.resources[resource];
  const std::string& pass = d.passes[pass_].name;
  if (!is_write(access)) {
    d.errors.push_back(fmt::format("pass '{}' declares {} of '{}' as a write; use read()", pass,
                                   access_name(access), r.name));
    return version;
  }
  if (r.origin == Origin::HistoryPrevious || (r.origin == Origin::Imported && r.import.read_only)) {
    d.errors.push_back(fmt::format("pass '{}' writes '{}', which is read-only ({})", pass, r.name,
                                   origin_name(r.origin)));
    return version;
  }
  if (version != r.latest_version) {
    const uint32_t other = version < r.writers.size() ? r.writers[version] : kInvalidIndex;
    d.errors.push_back(fmt::format(
        "two writers of '{}' version {}: pass '{}' and pass '{}' (write the newest handle)", r.name,
        version, other == kInvalidIndex ? "?" : d.passes[other].name, pass));
    return version;
  }
  r.buffer_usage |= buffer_usage(access);
  r.image_usage |= image_usage(access);
  d.passes[pass_].uses.push_back({resource, version, access});
  r.writers.push_back(pass_);
  return ++r.latest_version;
}

void PassBuilder::side_effect() {
  graph_.decl_.passes[pass_].side_effect = true;
}

// ---- RenderGraph ----

void RenderGraph::begin_frame() {
  decl_ = {};
  compiled_ = {};
  baked_ = false;
  compiled_this_frame_ = false;
  history_reads_.clear();
  history_.begin_frame();
}

uint32_t RenderGraph::add_resource(ResourceDecl resource) {
  decl_.resources.push_back(std::move(resource));
  return static_cast<uint32_t>(decl_.resources.size() - 1);
}

BufferHandle RenderGraph::create_buffer(std::string_view name, const BufferDesc& desc) {
  ResourceDecl r;
  r.name = name;
  r.buffer = desc;
  if (desc.size == 0) decl_.errors.push_back(fmt::format("buffer '{}' has size 0", name));
  return {add_resource(std::move(r)), 0};
}

ImageHandle RenderGraph::create_image(std::string_view name, const ImageDesc& desc) {
  ResourceDecl r;
  r.name = name;
  r.is_image = true;
  r.image = desc;
  if (desc.extent.width == 0 || desc.extent.height == 0 || desc.format == VK_FORMAT_UNDEFINED)
    decl_.errors.push_back(fmt::format("image '{}' has a zero extent or no format", name));
  return {add_resource(std::move(r)), 0};
}

BufferHandle RenderGraph::import_buffer(std::string_view name, VkBuffer buffer,
                                        const BufferDesc& desc, const ImportInfo& info) {
  ResourceDecl r;
  r.name = name;
  r.buffer = desc;
  r.origin = Origin::Imported;
  r.import = info;
  r.imported_buffer = buffer;
  return {add_resource(std::move(r)), 0};
}

ImageHandle RenderGraph::import_image(std::string_view name, VkImage image, VkImageView view,
                                      const ImageDesc& desc, const ImportInfo& info) {
  ResourceDecl r;
  r.name = name;
  r.is_image = true;
  r.image = desc;
  r.origin = Origin::Imported;
  r.import = info;
  r.imported_image = image;
  r.imported_view = view;
  return {add_resource(std::move(r)), 0};
}

uint32_t RenderGraph::declare_history(std::string_view name, const HistoryDesc& desc) {
  const HistoryTracker::Slots slots = history_.declare(name, desc);
  ResourceDecl r;
  r.name = name;
  r.is_image = std::holds_alternative<ImageDesc>(desc);
  if (r.is_image)
    r.image = std::get<ImageDesc>(desc);
  else
    r.buffer = std::get<BufferDesc>(desc);
  r.origin = Origin::History;
  r.history_slot = slots.write;
  r.import.initial = history_.slot_state(name, slots.write);
  const uint32_t index = add_resource(std::move(r));
  history_reads_[index] = {slots.read, slots.read_valid, kInvalidIndex};
  return index;
}

BufferHandle RenderGraph::create_history_buffer(std::string_view name, const BufferDesc& desc) {
  return {declare_history(name, desc), 0};
}

ImageHandle RenderGraph::create_history_image(std::string_view name, const ImageDesc& desc) {
  return {declare_history(name, desc), 0};
}

uint32_t RenderGraph::history_of(uint32_t current, bool image) {
  auto it = history_reads_.find(current);
  if (it == history_reads_.end() || decl_.resources[current].is_image != image) {
    decl_.errors.push_back(fmt::format(
        "history() of '{}': not a history {} (declare it with create_history_{})",
        current < decl_.resources.size() ? decl_.resources[current].name : "invalid handle",
        image ? "image" : "buffer", image ? "image" : "buffer"));
    return kInvalidIndex;
  }
  HistoryRead& read = it->second;
  if (!read.valid) return kInvalidIndex;
  if (read.resource == kInvalidIndex) {
    ResourceDecl r = decl_.resources[current];
    r.origin = Origin::HistoryPrevious;
    r.history_slot = read.slot;
    r.import.initial = history_.slot_state(r.name, read.slot);
    r.latest_version = 0;
    r.writers.clear();
    r.buffer_usage = 0;
    r.image_usage = 0;
    read.resource = add_resource(std::move(r));
  }
  return read.resource;
}

PassBuilder RenderGraph::begin_pass(std::string_view name, PassKind kind) {
  if (baked_) throw RenderGraphError(fmt::format("pass '{}' added after bake()", name));
  PassDecl pass;
  pass.name = name;
  pass.kind = kind;
  decl_.passes.push_back(std::move(pass));
  return PassBuilder(*this, static_cast<uint32_t>(decl_.passes.size() - 1));
}

const CompiledGraph& RenderGraph::bake(const CompileOptions& options) {
  compiled_ = compile_graph(decl_, options);
  baked_ = true;
  compiled_this_frame_ = true;
  return compiled_;
}

void RenderGraph::end_frame() {
  if (!baked_) return;
  for (uint32_t r = 0; r < decl_.resources.size(); ++r) {
    const ResourceDecl& res = decl_.resources[r];
    if (res.origin == Origin::History && res.latest_version > 0) history_.mark_written(res.name);
  }
  // Carry each used slot's final sync state into the next frame's barriers.
  for (uint32_t r = 0; r < decl_.resources.size(); ++r) {
    const ResourceDecl& res = decl_.resources[r];
    const bool persistent = res.origin == Origin::History || res.origin == Origin::HistoryPrevious;
    if (persistent && compiled_.lifetimes[r].used())
      history_.set_slot_state(res.name, res.history_slot, compiled_.final_states[r]);
  }
  baked_ = false;
}

}  // namespace lantern::runtime::graph
