// GraphExecutor: physical resources for a baked graph and the per-pass recording loop.
#include "runtime/graph/graph_executor.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/graph/barrier_recorder.h"
#include "runtime/graph/transient_create_info.h"

namespace lantern::runtime::graph {
namespace {

// A graph buffer's texel view; none where the buffer holds no whole texel or more than the
// device allows in one view (PassContext::texel_view then names the buffer).
BufferView texel_view(Device& device, VkBuffer buffer, VkDeviceSize size, std::string_view name) {
  const VkDeviceSize texels = size / kGraphTexelBytes;
  if (texels == 0 || texels > device.properties().limits.maxTexelBufferElements) return {};
  return BufferView(device, buffer, size, kGraphTexelFormat, fmt::format("{}.texels", name));
}

}  // namespace

GraphExecutor::GraphExecutor(Device& device) : device_(device) {
  barrier2_ = device.fn().cmd_pipeline_barrier2;
}

GraphExecutor::~GraphExecutor() {
  release_transients();
}

void GraphExecutor::use_synchronization2(bool enabled) {
  barrier2_ = enabled ? device_.fn().cmd_pipeline_barrier2 : nullptr;
}

CompileOptions GraphExecutor::compile_options() const {
  CompileOptions options;
  const VkDevice device = device_.handle();
  const VkDeviceSize granularity = device_.caps().buffer_image_granularity;
  // Ask the driver through a short-lived object with the exact create-info used later.
  options.memory_requirement = [device, granularity](const ResourceDecl& r) {
    VkMemoryRequirements req{};
    if (r.is_image) {
      const VkImageCreateInfo info = transient_image_info(r);
      VkImage image = VK_NULL_HANDLE;
      VK_CHECK(vkCreateImage(device, &info, nullptr, &image));
      vkGetImageMemoryRequirements(device, image, &req);
      vkDestroyImage(device, image, nullptr);
    } else {
      const VkBufferCreateInfo info = transient_buffer_info(r);
      VkBuffer buffer = VK_NULL_HANDLE;
      VK_CHECK(vkCreateBuffer(device, &info, nullptr, &buffer));
      vkGetBufferMemoryRequirements(device, buffer, &req);
      vkDestroyBuffer(device, buffer, nullptr);
    }
    // Buffers and images share the block: keep them bufferImageGranularity apart.
    return MemoryRequirement{req.size, std::max(req.alignment, granularity)};
  };
  return options;
}

void GraphExecutor::release_transients() {
  const VkDevice device = device_.handle();
  for (Transient& t : transients_) {
    t.texels = {};
    if (t.view != VK_NULL_HANDLE) vkDestroyImageView(device, t.view, nullptr);
    if (t.image != VK_NULL_HANDLE) vkDestroyImage(device, t.image, nullptr);
    if (t.buffer != VK_NULL_HANDLE) vkDestroyBuffer(device, t.buffer, nullptr);
  }
  transients_.clear();
  transient_resources_.clear();
  if (transient_allocation_) device_.memory().free(transient_allocation_);
  transient_allocation_ = {};
  transient_signature_.clear();
}

void GraphExecutor::realize_transients(const GraphDecl& decl, const CompiledGraph& compiled) {
  // The frame's shape: same signature → same objects at the same offsets, reuse them.
  std::string signature = fmt::format("{}:", compiled.alias_plan.block_size);
  for (size_t i = 0; i < compiled.aliased.size(); ++i) {
    const ResourceDecl& r = decl.resources[compiled.aliased[i]];
    signature +=
        fmt::format("{}|{}|{}x{}x{}|{}|{}|{}|{};", r.is_image, r.buffer.size, r.image.extent.width,
                    r.image.extent.height, r.image.extent.depth, static_cast<int>(r.image.format),
                    r.buffer_usage, r.image_usage, compiled.alias_plan.offsets[i]);
  }
  if (signature == transient_signature_) {
    // Same objects, but resource indices may differ from last frame (e.g. a history read added).
    transient_resources_ = compiled.aliased;
    return;
  }
  if (!transients_.empty()) device_.wait_idle();  // old objects may still be in flight
  release_transients();
  if (compiled.aliased.empty()) {
    transient_signature_ = signature;
    return;
  }

  const VkDevice device = device_.handle();
  VkMemoryRequirements block{};
  block.size = compiled.alias_plan.block_size;
  block.alignment = 1;
  block.memoryTypeBits = ~0u;
  bool any_image = false;
  for (size_t i = 0; i < compiled.aliased.size(); ++i) {
    const ResourceDecl& r = decl.resources[compiled.aliased[i]];
    Transient t;
    VkMemoryRequirements req{};
    if (r.is_image) {
      const VkImageCreateInfo info = transient_image_info(r);
      VK_CHECK(vkCreateImage(device, &info, nullptr, &t.image));
      vkGetImageMemoryRequirements(device, t.image, &req);
      device_.set_name(t.image, r.name);
      any_image = true;
    } else {
      const VkBufferCreateInfo info = transient_buffer_info(r);
      VK_CHECK(vkCreateBuffer(device, &info, nullptr, &t.buffer));
      vkGetBufferMemoryRequirements(device, t.buffer, &req);
      device_.set_name(t.buffer, r.name);
    }
    transients_.push_back(std::move(t));
    transient_resources_.push_back(compiled.aliased[i]);
    if (req.size > compiled.alias_requests[i].size)
      throw RenderGraphError(
          fmt::format("render graph: '{}' needs {} B but was planned with {} B (bake with "
                      "GraphExecutor::compile_options())",
                      r.name, req.size, compiled.alias_requests[i].size));
    block.alignment = std::max(block.alignment, req.alignment);
    block.memoryTypeBits &= req.memoryTypeBits;
  }
  if (block.memoryTypeBits == 0)
    throw RenderGraphError("render graph: transient resources have no common memory type");
  transient_allocation_ =
      device_.memory().allocate(block, MemoryUsage::DeviceLocal,
                                any_image ? ResourceKind::OptimalImage : ResourceKind::Linear);
  for (size_t i = 0; i < transients_.size(); ++i) {
    Transient& t = transients_[i];
    const VkDeviceSize offset = transient_allocation_.offset + compiled.alias_plan.offsets[i];
    if (t.image != VK_NULL_HANDLE) {
      VK_CHECK(vkBindImageMemory(device, t.image, transient_allocation_.memory, offset));
      const VkImageViewCreateInfo view =
          transient_view_info(decl.resources[transient_resources_[i]], t.image);
      VK_CHECK(vkCreateImageView(device, &view, nullptr, &t.view));
    } else {
      VK_CHECK(vkBindBufferMemory(device, t.buffer, transient_allocation_.memory, offset));
      const ResourceDecl& r = decl.resources[transient_resources_[i]];
      if ((r.buffer_usage & VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT) != 0)
        t.texels = texel_view(device_, t.buffer, r.buffer.size, r.name);
    }
  }
  transient_signature_ = signature;
}

PhysicalResource GraphExecutor::realize_history(const ResourceDecl& r) {
  const HistoryDesc desc = r.is_image ? HistoryDesc{r.image} : HistoryDesc{r.buffer};
  // Usage every history gets, plus whatever this frame declares; recreated if that grows. A
  // history buffer is written in one frame and may be read as texels in the next: both slots
  // are texel buffers from the start (a later-grown usage would recreate one and lose it).
  const VkFlags usage =
      r.is_image ? (r.image_usage | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT)
                 : (r.buffer_usage | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                    VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
  const auto key = std::make_pair(r.name, r.history_slot);
  auto it = history_.find(key);
  if (it == history_.end() || !(it->second.desc == desc) || (it->second.usage & usage) != usage) {
    if (it != history_.end()) {
      device_.wait_idle();
      it->second.texels = {};  // the old view goes before the buffer it views
    }
    const std::string name = fmt::format("{}[{}]", r.name, r.history_slot);
    if (r.is_image) {
      if (r.image.extent.depth != 1 || r.image.mip_levels != 1 || r.image.array_layers != 1)
        throw RenderGraphError(fmt::format(
            "render graph: history image '{}' must be 2D with one mip and one layer", r.name));
      Image image(device_, {.width = r.image.extent.width,
                            .height = r.image.extent.height,
                            .format = r.image.format,
                            .usage = usage,
                            .name = name});
      it = history_.insert_or_assign(key, HistorySlot{desc, usage, std::move(image)}).first;
    } else {
      Buffer buffer(device_, {.size = r.buffer.size,
                              .usage = usage,
                              .memory = MemoryUsage::DeviceLocal,
                              .name = name});
      BufferView texels = texel_view(device_, buffer.handle(), buffer.size(), name);
      it = history_
               .insert_or_assign(key, HistorySlot{desc, usage, std::move(buffer), std::move(texels)})
               .first;
    }
  }
  PhysicalResource p;
  if (const Image* image = std::get_if<Image>(&it->second.object)) {
    p.image = image->handle();
    p.view = image->view();
  } else {
    const Buffer& buffer = std::get<Buffer>(it->second.object);
    p.buffer = buffer.handle();
    p.size = buffer.size();
    p.texel_view = it->second.texels.handle();
  }
  return p;
}

void GraphExecutor::record(RenderGraph& graph, VkCommandBuffer cmd, GpuTimer* timer) {
  if (!graph.baked()) throw RenderGraphError("render graph: record() before bake()");
  const GraphDecl& decl = graph.decl();
  const CompiledGraph& compiled = graph.compiled();

  // Resolve every resource to its Vulkan objects.
  realize_transients(decl, compiled);
  std::vector<PhysicalResource> physical(decl.resources.size());
  for (size_t i = 0; i < transients_.size(); ++i)
    physical[transient_resources_[i]] = {transients_[i].buffer,
                                         decl.resources[transient_resources_[i]].buffer.size,
                                         transients_[i].image, transients_[i].view,
                                         transients_[i].texels.handle()};
  for (uint32_t r = 0; r < decl.resources.size(); ++r) {
    const ResourceDecl& res = decl.resources[r];
    if (res.origin == Origin::Imported)
      physical[r] = {res.imported_buffer, res.buffer.size, res.imported_image, res.imported_view};
    else if (res.origin != Origin::Transient && compiled.lifetimes[r].used())
      physical[r] = realize_history(res);
  }

  // Each pass: label and timestamps, its barriers, its commands. (An exception from a pass
  // leaves `cmd` unusable anyway, so the open scope is not closed on that path.)
  const auto record_pass = [&](VkCommandBuffer target, const CompiledPass& compiled_pass) {
    const PassDecl& pass = decl.passes[compiled_pass.pass];
    if (timer != nullptr)
      timer->begin(target, pass.name);  // timestamps + debug label
    else
      device_.begin_label(target, pass.name);
    record_barriers(target, barrier2_, compiled_pass.before, decl, physical);
    if (pass.execute) {
      PassContext context(target, decl, compiled_pass.pass, physical);
      pass.execute(context);
    }
    if (timer != nullptr)
      timer->end(target);
    else
      device_.end_label(target);
  };

  const auto is_host = [&](std::size_t i) {
    return decl.passes[compiled.passes[i].pass].kind == PassKind::Host;
  };
  const auto run_host = [&](const CompiledPass& host_pass) {
    const PassDecl& pass = decl.passes[host_pass.pass];
    const auto start = std::chrono::steady_clock::now();
    if (pass.execute) {
      PassContext context(VK_NULL_HANDLE, decl, host_pass.pass, physical);
      pass.execute(context);
    }
    if (timer != nullptr) {
      timer->add_host(pass.name, std::chrono::duration<double, std::milli>(
                                     std::chrono::steady_clock::now() - start)
                                     .count());
    }
  };
  // A host pass splits the frame: the passes before it (and the barriers that make their writes
  // visible to the host) are submitted on their own and waited for, the host pass runs on this
  // thread (timed as a host scope), and recording goes on. A host pass that needs no barrier
  // uses nothing an earlier pass of the frame touches (and nothing a finished frame left
  // unsynchronised): it runs at once, without that submission and wait, and the passes before it
  // go into the next segment (so it overlaps the frames still in flight instead of waiting for
  // them). What follows the last waiting host pass is recorded into `cmd`, which the caller
  // submits.
  std::size_t next = 0;
  for (std::size_t i = 0; i < compiled.passes.size(); ++i) {
    if (!is_host(i)) continue;
    const CompiledPass& host_pass = compiled.passes[i];
    if (host_pass.before.empty()) {
      run_host(host_pass);
      continue;
    }
    device_.submit_and_wait([&](VkCommandBuffer segment) {
      for (; next < i; ++next)
        if (!is_host(next)) record_pass(segment, compiled.passes[next]);
      record_barriers(segment, barrier2_, host_pass.before, decl, physical);
    });
    run_host(host_pass);
    next = i + 1;
  }
  for (; next < compiled.passes.size(); ++next)
    if (!is_host(next)) record_pass(cmd, compiled.passes[next]);
  record_barriers(cmd, barrier2_, compiled.after, decl, physical);
}

}  // namespace lantern::runtime::graph
