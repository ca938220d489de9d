// Timestamp query pool with named, nestable scopes.
#include "runtime/gpu/gpu_timer.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"

namespace lantern::runtime {

GpuTimer::GpuTimer(Device& device, std::uint32_t max_scopes)
    : device_(device), max_scopes_(max_scopes) {
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = 2 * max_scopes;
  VK_CHECK(vkCreateQueryPool(device.handle(), &info, nullptr, &pool_));
  device.set_name(pool_, "lantern.gpu_timer");
}

GpuTimer::~GpuTimer() {
  vkDestroyQueryPool(device_.handle(), pool_, nullptr);
}

void GpuTimer::reset(VkCommandBuffer cmd) {
  vkCmdResetQueryPool(cmd, pool_, 0, 2 * max_scopes_);
  entries_.clear();
  open_.clear();
}

void GpuTimer::reset_on_host() {
  vkResetQueryPool(device_.handle(), pool_, 0, 2 * max_scopes_);
  entries_.clear();
  open_.clear();
}

void GpuTimer::add_host(std::string_view name, double ms) {
  if (entries_.size() >= max_scopes_)
    throw RuntimeError(
        fmt::format("GpuTimer: more than {} scopes in one frame (at '{}')", max_scopes_, name));
  entries_.push_back({std::string(name), static_cast<std::uint32_t>(open_.size()), true, ms});
}

void GpuTimer::begin(VkCommandBuffer cmd, std::string_view name) {
  if (entries_.size() >= max_scopes_)
    throw RuntimeError(
        fmt::format("GpuTimer: more than {} scopes in one frame (at '{}')", max_scopes_, name));
  const auto index = static_cast<std::uint32_t>(entries_.size());
  entries_.push_back({std::string(name), static_cast<std::uint32_t>(open_.size()), false});
  open_.push_back(index);
  device_.begin_label(cmd, name);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_, 2 * index);
}

void GpuTimer::end(VkCommandBuffer cmd) {
  if (open_.empty()) throw RuntimeError("GpuTimer::end without a matching begin");
  const std::uint32_t index = open_.back();
  open_.pop_back();
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 2 * index + 1);
  device_.end_label(cmd);
  entries_[index].closed = true;
}

std::vector<GpuTimer::Result> GpuTimer::resolve() const {
  if (!open_.empty())
    throw RuntimeError(
        fmt::format("GpuTimer: scope '{}' was never ended", entries_[open_.back()].name));
  std::vector<Result> results;
  if (entries_.empty()) return results;
  // Host scopes wrote no queries: read the GPU scopes' in runs between them.
  std::vector<std::uint64_t> ticks(2 * entries_.size(), 0);
  for (std::size_t begin = 0; begin < entries_.size();) {
    if (entries_[begin].host_ms >= 0.0) {
      ++begin;
      continue;
    }
    std::size_t end = begin;
    while (end < entries_.size() && entries_[end].host_ms < 0.0) ++end;
    const auto count = static_cast<std::uint32_t>(2 * (end - begin));
    VK_CHECK(vkGetQueryPoolResults(device_.handle(), pool_, static_cast<std::uint32_t>(2 * begin),
                                   count, count * sizeof(std::uint64_t), &ticks[2 * begin],
                                   sizeof(std::uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    begin = end;
  }
  const std::uint32_t bits = device_.caps().timestamp_valid_bits;
  const std::uint64_t mask = bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1;
  const double ns_per_tick = device_.caps().timestamp_period_ns;
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    if (entries_[i].host_ms >= 0.0) {
      results.push_back({entries_[i].name, entries_[i].host_ms, entries_[i].depth});
      continue;
    }
    const std::uint64_t elapsed =
        ((ticks[2 * i + 1] & mask) - (ticks[2 * i] & mask)) & mask;  // wrap-safe
    results.push_back(
        {entries_[i].name, static_cast<double>(elapsed) * ns_per_tick * 1e-6, entries_[i].depth});
  }
  return results;
}

}  // namespace lantern::runtime
