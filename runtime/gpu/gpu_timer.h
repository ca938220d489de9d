// GPU timestamps per named pass: `timer.reset(cmd)` at the start of a frame's command buffer,
// `auto s = timer.scope(cmd, "restir.initial")` (or begin/end) around each pass, and
// `timer.resolve()` after the frame's fence for milliseconds per scope. Scopes nest; each also
// opens a debug label of the same name.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lantern::runtime {

class Device;

class GpuTimer {
 public:
  struct Result {
    std::string name;
    double ms = 0.0;
    std::uint32_t depth = 0;  // nesting level
  };

  GpuTimer(Device& device, std::uint32_t max_scopes = 64);
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  void reset(VkCommandBuffer cmd);  // outside any render pass; forgets the previous frame's scopes
  // The same from the host (vkResetQueryPool): for a frame recorded into several submissions
  // (render-graph host passes), whose first submission is not the one a reset(cmd) would be in.
  // Call only when no submitted work still writes this timer's queries.
  void reset_on_host();
  void begin(VkCommandBuffer cmd, std::string_view name);
  void end(VkCommandBuffer cmd);
  // A scope timed on the host (a render-graph host pass), reported among the GPU scopes in order.
  void add_host(std::string_view name, double ms);
  // Results in begin() order; call after the command buffer completed (waits for the queries).
  std::vector<Result> resolve() const;

  class Scope {
   public:
    Scope(GpuTimer& timer, VkCommandBuffer cmd, std::string_view name) : timer_(timer), cmd_(cmd) {
      timer_.begin(cmd_, name);
    }
    ~Scope() { timer_.end(cmd_); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    GpuTimer& timer_;
    VkCommandBuffer cmd_;
  };
  [[nodiscard]] Scope scope(VkCommandBuffer cmd, std::string_view name) {
    return Scope(*this, cmd, name);
  }

 private:
  struct Entry {
    std::string name;
    std::uint32_t depth = 0;
    bool closed = false;
    double host_ms = -1.0;  // >= 0: a host scope (no queries)
  };
  Device& device_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  std::uint32_t max_scopes_;
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> open_;  // stack of entry indices
};

}  // namespace lantern::runtime
