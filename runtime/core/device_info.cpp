// Physical-device queries and the device selection rule.
#include "runtime/core/device_info.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstring>

#include "engine/core/error.h"
#include "runtime/core/vk_check.h"

namespace lantern::runtime {
namespace {

const char* type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "cpu";
    default:
      return "other";
  }
}

bool has(const std::vector<VkExtensionProperties>& extensions, const char* name) {
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

int auto_rank(const std::string& type) {
  if (type == "discrete") return 0;
  if (type == "integrated") return 1;
  if (type == "virtual") return 2;
  if (type == "cpu") return 3;
  return 4;
}

}  // namespace

std::string version_string(std::uint32_t v) {
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(v), VK_API_VERSION_MINOR(v),
                     VK_API_VERSION_PATCH(v));
}

DeviceInfo query_device_info(VkPhysicalDevice device, std::uint32_t index) {
  std::uint32_t count = 0;
  VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr));
  std::vector<VkExtensionProperties> extensions(count);
  VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()));

  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
  vkGetPhysicalDeviceProperties2(device, &props);
  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &v12};
  vkGetPhysicalDeviceFeatures2(device, &features);
  VkPhysicalDeviceMemoryProperties memory{};
  vkGetPhysicalDeviceMemoryProperties(device, &memory);

  DeviceInfo info;
  info.index = index;
  info.name = props.properties.deviceName;
  info.type = type_name(props.properties.deviceType);
  info.api_version = version_string(props.properties.apiVersion);
  info.driver = fmt::format("{} {}", driver.driverName, driver.driverInfo);
  info.ray_query = has(extensions, VK_KHR_RAY_QUERY_EXTENSION_NAME) &&
                   has(extensions, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME) &&
                   has(extensions, VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME) &&
                   v12.bufferDeviceAddress;
  info.descriptor_indexing = v12.descriptorIndexing && v12.runtimeDescriptorArray &&
                             v12.descriptorBindingPartiallyBound &&
                             v12.shaderSampledImageArrayNonUniformIndexing;
  info.push_descriptor = has(extensions, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
  for (std::uint32_t h = 0; h < memory.memoryHeapCount; ++h)
    if ((memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) != 0)
      info.device_local_bytes =
          std::max<std::uint64_t>(info.device_local_bytes, memory.memoryHeaps[h].size);
  std::memcpy(info.pipeline_cache_uuid.data(), props.properties.pipelineCacheUUID, VK_UUID_SIZE);
  return info;
}

std::string describe_devices(std::span<const DeviceInfo> devices) {
  if (devices.empty()) return "no Vulkan devices found";
  std::string text;
  for (const auto& d : devices)
    text += fmt::format("{}{}: {} [{}]", text.empty() ? "" : "; ", d.index, d.name, d.type);
  return text;
}

std::uint32_t select_device(std::span<const DeviceInfo> devices, const std::string& selector) {
  auto fail = [&](const std::string& why) -> std::uint32_t {
    throw InputError(
        fmt::format("--device {}: {} (available: {})", selector, why, describe_devices(devices)));
  };
  if (devices.empty()) fail("no Vulkan devices found (is mesa-vulkan-drivers installed?)");

  if (selector == "auto" || selector == "gpu" || selector == "cpu") {
    const DeviceInfo* best = nullptr;
    for (const auto& d : devices) {
      const bool allowed =
          selector == "auto" ||
          (selector == "gpu" && (d.type == "discrete" || d.type == "integrated")) ||
          (selector == "cpu" && d.type == "cpu");
      if (allowed && (best == nullptr || auto_rank(d.type) < auto_rank(best->type))) best = &d;
    }
    if (best == nullptr) fail(fmt::format("no {} device", selector == "gpu" ? "GPU" : "CPU"));
    return best->index;
  }

  std::uint32_t index = 0;
  const char* end = selector.data() + selector.size();
  const auto [ptr, ec] = std::from_chars(selector.data(), end, index);
  if (selector.empty() || ec != std::errc() || ptr != end)
    fail("expected auto, cpu, gpu or a device index");
  for (const auto& d : devices)
    if (d.index == index) return index;
  return fail(fmt::format("device index {} out of range", index));
}

}  // namespace lantern::runtime
