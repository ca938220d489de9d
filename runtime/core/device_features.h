// Feature negotiation: what Lantern requires of a device, what it uses when present, and the
// resulting DeviceCaps that the rest of the engine branches on (never on raw Vulkan features).
//
// Required: Vulkan 1.2, a graphics+compute queue with timestamps, VK_KHR_push_descriptor,
// synchronization2 (core 1.3 or VK_KHR_synchronization2; the render graph emits only
// vkCmdPipelineBarrier2), storage buffers/images, hostQueryReset and timeline semaphores.
// Optional (see DeviceCaps): ray query (+ acceleration structure + buffer device address, enabled
// together), descriptor indexing, dynamic rendering, float16/int64/int8 arithmetic.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace lantern::runtime {

struct DeviceCaps {
  std::uint32_t api_version = 0;       // effective: min(device, instance 1.3)
  bool ray_query = false;              // VK_KHR_ray_query + VK_KHR_acceleration_structure
  bool buffer_device_address = false;  // enabled together with ray query
  bool descriptor_indexing = false;    // bindless arrays: non-uniform indexing, partially bound
  bool dynamic_rendering = false;      // needed by GraphicsPipeline
  bool synchronization2 = true;        // always (required)
  bool shader_float16 = false;
  bool shader_int64 = false;
  bool shader_int8 = false;
  bool storage_image_without_format = false;  // read/write storage images with no format qualifier
  bool debug_utils = false;                   // object names and command labels
  float timestamp_period_ns = 1.0f;           // nanoseconds per timestamp tick
  std::uint32_t timestamp_valid_bits = 0;
  std::uint32_t max_push_descriptors = 0;
  std::uint32_t max_push_constant_bytes = 0;
  std::uint32_t subgroup_size = 0;
  VkDeviceSize buffer_image_granularity = 1;
  VkDeviceSize max_storage_buffer_range = 0;
  VkDeviceSize max_memory_allocation_size = 0;
};

// Owns the VkPhysicalDevice*Features structs to enable, chained by chain().
class FeatureNegotiation {
 public:
  // Throws lantern::RuntimeError listing everything required that the device lacks.
  FeatureNegotiation(VkPhysicalDevice device, std::uint32_t queue_timestamp_bits);
  FeatureNegotiation(const FeatureNegotiation&) = delete;
  FeatureNegotiation& operator=(const FeatureNegotiation&) = delete;

  const DeviceCaps& caps() const { return caps_; }
  const std::vector<const char*>& extensions() const { return extensions_; }
  // The pNext chain for VkDeviceCreateInfo (features to enable).
  const VkPhysicalDeviceFeatures2* chain();

 private:
  DeviceCaps caps_;
  std::vector<const char*> extensions_;
  VkPhysicalDeviceFeatures2 features_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDeviceVulkan11Features v11_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceVulkan12Features v12_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan13Features v13_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceSynchronization2FeaturesKHR sync2_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES_KHR};
  VkPhysicalDeviceDynamicRenderingFeaturesKHR dynamic_rendering_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES_KHR};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR acceleration_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayQueryFeaturesKHR ray_query_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
};

}  // namespace lantern::runtime
