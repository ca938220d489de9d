// GraphExecutor: turns a baked RenderGraph into commands on a Device. It creates the transient
// resources in one aliased memory block (reused while the frame's shape stays the same), keeps
// the history pairs, and records per pass: a debug label and GPU timestamps under the pass's
// module.stage name (runtime::GpuTimer), the pass's barriers, then its execute callback.
#pragma once

#include <vulkan/vulkan.h>

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "runtime/gpu/buffer.h"
#include "runtime/gpu/buffer_view.h"
#include "runtime/gpu/image.h"
#include "runtime/gpu/memory_allocator.h"
#include "runtime/graph/render_graph.h"

namespace lantern::runtime {
class Device;
class GpuTimer;
}  // namespace lantern::runtime

namespace lantern::runtime::graph {

class GraphExecutor {
 public:
  explicit GraphExecutor(Device& device);
  ~GraphExecutor();
  GraphExecutor(const GraphExecutor&) = delete;
  GraphExecutor& operator=(const GraphExecutor&) = delete;

  // Compile options with this device's real memory requirements: pass to RenderGraph::bake().
  [[nodiscard]] CompileOptions compile_options() const;

  // Records the baked frame of `graph` into `cmd`. Call between bake() and end_frame(). With a
  // timer (reset by the caller before the frame's first submission), each pass is a timed scope
  // that also carries the debug label; without one, passes still get labels. When the frame's
  // transient layout changes, waits for the device before freeing the old one. Host passes
  // (PassKind::Host) split the frame: what precedes each is submitted and waited for first (so
  // reset a timer with GpuTimer::reset_on_host, not into `cmd`), and only what follows the last
  // lands in `cmd`; a host pass that needs no barrier (its resources untouched earlier in the
  // frame and imported without a prior use to wait for) runs at once, without that wait.
  void record(RenderGraph& graph, VkCommandBuffer cmd, GpuTimer* timer = nullptr);

  // Test switch: record Vulkan 1.0 barriers even when synchronization2 is available.
  void use_synchronization2(bool enabled);
  [[nodiscard]] bool synchronization2() const { return barrier2_ != nullptr; }
  // Bytes of the aliased transient block currently held.
  [[nodiscard]] VkDeviceSize transient_bytes() const { return transient_allocation_.size; }

 private:
  struct Transient {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    BufferView texels;  // where the frame reads the buffer as texels
  };
  struct HistorySlot {
    HistoryDesc desc;
    VkFlags usage = 0;
    std::variant<Buffer, Image> object;
    BufferView texels;  // every history buffer has one (a later frame may read texels)
  };

  void realize_transients(const GraphDecl& decl, const CompiledGraph& compiled);
  void release_transients();
  PhysicalResource realize_history(const ResourceDecl& resource);

  Device& device_;
  PFN_vkCmdPipelineBarrier2KHR barrier2_ = nullptr;
  std::string transient_signature_;
  std::vector<Transient> transients_;
  std::vector<uint32_t> transient_resources_;  // decl resource index per transients_ entry
  Allocation transient_allocation_;
  std::map<std::pair<std::string, uint32_t>, HistorySlot> history_;
};

}  // namespace lantern::runtime::graph
