// Maps Vulkan handle types to VkObjectType so Device::set_name(handle, "name") works for any
// handle.
#pragma once

#include <vulkan/vulkan.h>

namespace lantern::runtime {

template <class Handle>
struct ObjectTypeOf;

#define LANTERN_OBJECT_TYPE(Handle, Type)       \
  template <>                                   \
  struct ObjectTypeOf<Handle> {                 \
    static constexpr VkObjectType value = Type; \
  }
LANTERN_OBJECT_TYPE(VkBuffer, VK_OBJECT_TYPE_BUFFER);
LANTERN_OBJECT_TYPE(VkImage, VK_OBJECT_TYPE_IMAGE);
LANTERN_OBJECT_TYPE(VkImageView, VK_OBJECT_TYPE_IMAGE_VIEW);
LANTERN_OBJECT_TYPE(VkSampler, VK_OBJECT_TYPE_SAMPLER);
LANTERN_OBJECT_TYPE(VkDeviceMemory, VK_OBJECT_TYPE_DEVICE_MEMORY);
LANTERN_OBJECT_TYPE(VkPipeline, VK_OBJECT_TYPE_PIPELINE);
LANTERN_OBJECT_TYPE(VkPipelineLayout, VK_OBJECT_TYPE_PIPELINE_LAYOUT);
LANTERN_OBJECT_TYPE(VkDescriptorSetLayout, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT);
LANTERN_OBJECT_TYPE(VkShaderModule, VK_OBJECT_TYPE_SHADER_MODULE);
LANTERN_OBJECT_TYPE(VkCommandBuffer, VK_OBJECT_TYPE_COMMAND_BUFFER);
LANTERN_OBJECT_TYPE(VkCommandPool, VK_OBJECT_TYPE_COMMAND_POOL);
LANTERN_OBJECT_TYPE(VkQueue, VK_OBJECT_TYPE_QUEUE);
LANTERN_OBJECT_TYPE(VkFence, VK_OBJECT_TYPE_FENCE);
LANTERN_OBJECT_TYPE(VkSemaphore, VK_OBJECT_TYPE_SEMAPHORE);
LANTERN_OBJECT_TYPE(VkQueryPool, VK_OBJECT_TYPE_QUERY_POOL);
LANTERN_OBJECT_TYPE(VkAccelerationStructureKHR, VK_OBJECT_TYPE_ACCELERATION_STRUCTURE_KHR);
#undef LANTERN_OBJECT_TYPE

}  // namespace lantern::runtime
