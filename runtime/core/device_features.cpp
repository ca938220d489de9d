// Feature negotiation: query supported features, enable what we need and what helps, fill
// DeviceCaps.
#include "runtime/core/device_features.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "engine/core/error.h"
#include "runtime/core/vk_check.h"

namespace lantern::runtime {

FeatureNegotiation::FeatureNegotiation(VkPhysicalDevice device,
                                       std::uint32_t queue_timestamp_bits) {
  std::uint32_t count = 0;
  VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr));
  std::vector<VkExtensionProperties> available(count);
  VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, available.data()));
  auto has = [&](const char* name) {
    return std::any_of(available.begin(), available.end(),
                       [&](const auto& e) { return std::strcmp(e.extensionName, name) == 0; });
  };

  VkPhysicalDevicePushDescriptorPropertiesKHR push{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PUSH_DESCRIPTOR_PROPERTIES_KHR};
  VkPhysicalDeviceVulkan11Properties p11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES,
                                         &push};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p11};
  vkGetPhysicalDeviceProperties2(device, &props);
  const VkPhysicalDeviceLimits& limits = props.properties.limits;
  caps_.api_version =
      std::min(props.properties.apiVersion, static_cast<std::uint32_t>(VK_API_VERSION_1_3));
  const bool core13 = caps_.api_version >= VK_API_VERSION_1_3;

  // What the device supports.
  VkPhysicalDeviceVulkan11Features s11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceVulkan12Features s12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &s11};
  VkPhysicalDeviceSynchronization2FeaturesKHR s_sync2{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES_KHR, &s12};
  VkPhysicalDeviceDynamicRenderingFeaturesKHR s_dyn{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES_KHR, &s_sync2};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR s_accel{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, &s_dyn};
  VkPhysicalDeviceRayQueryFeaturesKHR s_rq{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR,
                                           &s_accel};
  VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &s_rq};
  vkGetPhysicalDeviceFeatures2(device, &supported);
  const VkPhysicalDeviceFeatures& s10 = supported.features;

  std::vector<std::string> missing;
  auto require = [&](bool ok, const char* what) {
    if (!ok) missing.emplace_back(what);
  };
  require(props.properties.apiVersion >= VK_API_VERSION_1_2, "Vulkan 1.2");
  require(has(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME), VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
  require(queue_timestamp_bits > 0 && limits.timestampComputeAndGraphics,
          "timestamps on the graphics+compute queue");
  require(s12.hostQueryReset, "hostQueryReset");
  require(s12.timelineSemaphore, "timelineSemaphore");
  require(s10.fragmentStoresAndAtomics, "fragmentStoresAndAtomics");
  require(s10.shaderStorageImageExtendedFormats, "shaderStorageImageExtendedFormats");
  const bool sync2 =
      s_sync2.synchronization2 && (core13 || has(VK_KHR_SYNCHRONIZATION_2_EXTENSION_NAME));
  require(sync2, "synchronization2");
  if (!missing.empty()) {
    std::string list;
    for (const auto& m : missing) list += (list.empty() ? "" : ", ") + m;
    throw RuntimeError(fmt::format("Vulkan device '{}' lacks required features: {}",
                                   props.properties.deviceName, list));
  }

  // Required features.
  extensions_.push_back(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
  v12_.hostQueryReset = VK_TRUE;
  v12_.timelineSemaphore = VK_TRUE;
  features_.features.fragmentStoresAndAtomics = VK_TRUE;
  features_.features.shaderStorageImageExtendedFormats = VK_TRUE;
  if (core13) {
    v13_.synchronization2 = VK_TRUE;
  } else {
    extensions_.push_back(VK_KHR_SYNCHRONIZATION_2_EXTENSION_NAME);
    sync2_.synchronization2 = VK_TRUE;
  }

  // Optional features, reported in caps.
  features_.features.shaderInt64 = s10.shaderInt64;
  caps_.shader_int64 = s10.shaderInt64 == VK_TRUE;
  caps_.storage_image_without_format =
      s10.shaderStorageImageReadWithoutFormat && s10.shaderStorageImageWriteWithoutFormat;
  features_.features.shaderStorageImageReadWithoutFormat = s10.shaderStorageImageReadWithoutFormat;
  features_.features.shaderStorageImageWriteWithoutFormat =
      s10.shaderStorageImageWriteWithoutFormat;
  features_.features.samplerAnisotropy = s10.samplerAnisotropy;
  features_.features.independentBlend = s10.independentBlend;
  v11_.shaderDrawParameters = s11.shaderDrawParameters;
  v11_.storageBuffer16BitAccess = s11.storageBuffer16BitAccess;
  v12_.shaderFloat16 = s12.shaderFloat16;
  caps_.shader_float16 = s12.shaderFloat16 == VK_TRUE;
  v12_.shaderInt8 = s12.shaderInt8;
  caps_.shader_int8 = s12.shaderInt8 == VK_TRUE;
  v12_.storageBuffer8BitAccess = s12.storageBuffer8BitAccess;
  v12_.scalarBlockLayout = s12.scalarBlockLayout;

  caps_.descriptor_indexing = s12.descriptorIndexing && s12.runtimeDescriptorArray &&
                              s12.descriptorBindingPartiallyBound &&
                              s12.shaderSampledImageArrayNonUniformIndexing;
  if (caps_.descriptor_indexing) {
    v12_.descriptorIndexing = VK_TRUE;
    v12_.runtimeDescriptorArray = VK_TRUE;
    v12_.descriptorBindingPartiallyBound = VK_TRUE;
    v12_.descriptorBindingVariableDescriptorCount = s12.descriptorBindingVariableDescriptorCount;
    v12_.shaderSampledImageArrayNonUniformIndexing = VK_TRUE;
    v12_.shaderStorageBufferArrayNonUniformIndexing =
        s12.shaderStorageBufferArrayNonUniformIndexing;
    v12_.shaderStorageImageArrayNonUniformIndexing = s12.shaderStorageImageArrayNonUniformIndexing;
  }

  caps_.dynamic_rendering =
      s_dyn.dynamicRendering && (core13 || has(VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME));
  if (caps_.dynamic_rendering) {
    if (core13) {
      v13_.dynamicRendering = VK_TRUE;
    } else {
      extensions_.push_back(VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
      dynamic_rendering_.dynamicRendering = VK_TRUE;
    }
  }

  caps_.ray_query = has(VK_KHR_RAY_QUERY_EXTENSION_NAME) &&
                    has(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME) &&
                    has(VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME) && s_rq.rayQuery &&
                    s_accel.accelerationStructure && s12.bufferDeviceAddress;
  if (caps_.ray_query) {
    extensions_.push_back(VK_KHR_RAY_QUERY_EXTENSION_NAME);
    extensions_.push_back(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME);
    extensions_.push_back(VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME);
    ray_query_.rayQuery = VK_TRUE;
    acceleration_.accelerationStructure = VK_TRUE;
    v12_.bufferDeviceAddress = VK_TRUE;
    caps_.buffer_device_address = true;
  }

  caps_.timestamp_period_ns = limits.timestampPeriod;
  caps_.timestamp_valid_bits = queue_timestamp_bits;
  caps_.max_push_descriptors = push.maxPushDescriptors;
  caps_.max_push_constant_bytes = limits.maxPushConstantsSize;
  caps_.subgroup_size = p11.subgroupSize;
  caps_.buffer_image_granularity = limits.bufferImageGranularity;
  caps_.max_storage_buffer_range = limits.maxStorageBufferRange;
  caps_.max_memory_allocation_size = p11.maxMemoryAllocationSize;
}

const VkPhysicalDeviceFeatures2* FeatureNegotiation::chain() {
  // Only structs that are valid for this device version go in the chain.
  const bool core13 = caps_.api_version >= VK_API_VERSION_1_3;
  void* next = nullptr;
  auto link = [&](auto& s) {
    s.pNext = next;
    next = &s;
  };
  if (caps_.ray_query) {
    link(ray_query_);
    link(acceleration_);
  }
  if (core13) {
    link(v13_);
  } else {
    link(sync2_);
    if (caps_.dynamic_rendering) link(dynamic_rendering_);
  }
  link(v12_);
  link(v11_);
  features_.pNext = next;
  return &features_;
}

}  // namespace lantern::runtime
