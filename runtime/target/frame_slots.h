// Frames in flight: per slot a command pool and buffer, a fence that says the slot's last
// submission finished, and a semaphore for the swapchain acquire. Slot i is reused only after
// its fence, so at most `count` frames are queued on the GPU at once.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace lantern::runtime {

class Device;

class FrameSlots {
 public:
  FrameSlots(Device& device, std::uint32_t count);
  ~FrameSlots();
  FrameSlots(const FrameSlots&) = delete;
  FrameSlots& operator=(const FrameSlots&) = delete;

  std::uint32_t count() const { return static_cast<std::uint32_t>(slots_.size()); }
  // Blocks until slot `i`'s last submission completed.
  void wait(std::uint32_t i);
  // Resets the slot's pool and begins its command buffer (call after wait()).
  VkCommandBuffer begin(std::uint32_t i);
  // Ends and submits the slot's command buffer; optional semaphores (VK_NULL_HANDLE = none).
  void submit(std::uint32_t i, VkSemaphore wait, VkPipelineStageFlags wait_stage,
              VkSemaphore signal);
  VkSemaphore acquire_semaphore(std::uint32_t i) const { return slots_.at(i).acquired; }
  // Waits for every slot (before resizing resources the frames use).
  void wait_all();

 private:
  struct Slot {
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence done = VK_NULL_HANDLE;
    VkSemaphore acquired = VK_NULL_HANDLE;
  };
  void release();

  Device& device_;
  std::vector<Slot> slots_;
};

}  // namespace lantern::runtime
