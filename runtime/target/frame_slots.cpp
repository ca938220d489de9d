// Per-slot command recording and submission.
#include "runtime/target/frame_slots.h"

#include <fmt/format.h>

#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"

namespace lantern::runtime {

FrameSlots::FrameSlots(Device& device, std::uint32_t count) : device_(device) {
  const VkDevice vk = device_.handle();
  slots_.resize(count);
  try {
    for (std::uint32_t i = 0; i < count; ++i) {
      Slot& slot = slots_[i];
      VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
      pool_info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
      pool_info.queueFamilyIndex = device_.queue_family();
      VK_CHECK(vkCreateCommandPool(vk, &pool_info, nullptr, &slot.pool));
      VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
      alloc.commandPool = slot.pool;
      alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
      alloc.commandBufferCount = 1;
      VK_CHECK(vkAllocateCommandBuffers(vk, &alloc, &slot.cmd));
      VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
      fence_info.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // a fresh slot is free
      VK_CHECK(vkCreateFence(vk, &fence_info, nullptr, &slot.done));
      VkSemaphoreCreateInfo semaphore_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
      VK_CHECK(vkCreateSemaphore(vk, &semaphore_info, nullptr, &slot.acquired));
      device_.set_name(slot.cmd, fmt::format("frame.slot{}", i));
      device_.set_name(slot.acquired, fmt::format("frame.slot{}.acquired", i));
    }
  } catch (...) {
    release();
    throw;
  }
}

FrameSlots::~FrameSlots() {
  vkDeviceWaitIdle(device_.handle());
  release();
}

void FrameSlots::release() {
  const VkDevice vk = device_.handle();
  for (Slot& slot : slots_) {
    if (slot.acquired != VK_NULL_HANDLE) vkDestroySemaphore(vk, slot.acquired, nullptr);
    if (slot.done != VK_NULL_HANDLE) vkDestroyFence(vk, slot.done, nullptr);
    if (slot.pool != VK_NULL_HANDLE) vkDestroyCommandPool(vk, slot.pool, nullptr);
  }
  slots_.clear();
}

void FrameSlots::wait(std::uint32_t i) {
  VK_CHECK(vkWaitForFences(device_.handle(), 1, &slots_.at(i).done, VK_TRUE, UINT64_MAX));
}

void FrameSlots::wait_all() {
  for (std::uint32_t i = 0; i < count(); ++i) wait(i);
}

VkCommandBuffer FrameSlots::begin(std::uint32_t i) {
  Slot& slot = slots_.at(i);
  VK_CHECK(vkResetCommandPool(device_.handle(), slot.pool, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(slot.cmd, &begin));
  return slot.cmd;
}

void FrameSlots::submit(std::uint32_t i, VkSemaphore wait, VkPipelineStageFlags wait_stage,
                        VkSemaphore signal) {
  Slot& slot = slots_.at(i);
  VK_CHECK(vkEndCommandBuffer(slot.cmd));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = wait != VK_NULL_HANDLE ? 1u : 0u;
  submit.pWaitSemaphores = &wait;
  submit.pWaitDstStageMask = &wait_stage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &slot.cmd;
  submit.signalSemaphoreCount = signal != VK_NULL_HANDLE ? 1u : 0u;
  submit.pSignalSemaphores = &signal;
  VK_CHECK(vkResetFences(device_.handle(), 1, &slot.done));
  VK_CHECK(vkQueueSubmit(device_.queue(), 1, &submit, slot.done));
}

}  // namespace lantern::runtime
