// What a physical device is and offers, read without creating a logical device, and the
// `--device auto|cpu|gpu|INDEX` selection rule over a list of them (pure, unit-tested).
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace lantern::runtime {

struct DeviceInfo {
  std::uint32_t index = 0;  // position in vkEnumeratePhysicalDevices order (= --device INDEX)
  std::string name;         // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string type;         // "discrete" | "integrated" | "virtual" | "cpu" | "other"
  std::string api_version;  // "1.4.305"
  std::string driver;       // driver name and info, e.g. "llvmpipe Mesa 25.0.7"
  bool ray_query = false;   // VK_KHR_ray_query + VK_KHR_acceleration_structure
  bool descriptor_indexing = false;
  bool push_descriptor = false;
  std::uint64_t device_local_bytes = 0;  // size of the largest device-local heap
  std::array<std::uint8_t, VK_UUID_SIZE> pipeline_cache_uuid{};
};

// Reads properties, extensions and features of one physical device.
DeviceInfo query_device_info(VkPhysicalDevice device, std::uint32_t index);

// Picks a device by selector: "auto" (discrete GPU, else integrated, else virtual, else CPU),
// "gpu" (discrete or integrated), "cpu", or a decimal index. Throws lantern::InputError naming the
// devices available when the selector is malformed or matches nothing.
std::uint32_t select_device(std::span<const DeviceInfo> devices, const std::string& selector);

// "0: llvmpipe (...) [cpu]; 1: ..." for error messages.
std::string describe_devices(std::span<const DeviceInfo> devices);

std::string version_string(std::uint32_t vk_version);

}  // namespace lantern::runtime
