// runtime::Device: the one object that owns the Vulkan instance, validation messenger, chosen
// physical device, logical device, graphics+compute queue, command pool, memory allocator and
// on-disk pipeline cache.
//
// clang-format off
// Usage (headers under runtime/gpu/: buffer, shader_library, compute_pipeline, bindings,
// gpu_timer, transfer):
//   runtime::Device device({.selector = "auto"});   // logs the chosen device
//   runtime::ShaderLibrary shaders;                 // compiled SPIR-V (LANTERN_SHADER_DIR)
//   runtime::ComputePipelineDesc desc{.name = "test.fill"};
//   desc.constants.set("kMultiplier", 7u);          // specialisation constants by name
//   runtime::ComputePipeline fill(device, shaders.load("tests/runtime_fill.comp"), desc);
//   fill.warm_up();                                 // JIT now, not in the first timed frame
//   runtime::Buffer out(device, {.size = n * 4, .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
//                                .memory = runtime::MemoryUsage::Readback, .name = "fill.out"});
//   runtime::GpuTimer timer(device);
//   device.submit_and_wait([&](VkCommandBuffer cmd) {
//     timer.reset(cmd);
//     auto pass = timer.scope(cmd, "test.fill");    // timestamps + debug label
//     fill.bind(cmd, runtime::Bindings(fill).buffer("result", out));  // bind BY NAME
//     fill.push_constants(cmd, Push{n, 11});
//     fill.dispatch_threads(cmd, n);
//   });
//   auto values = runtime::read_buffer<std::uint32_t>(device, out);
//   double ms = timer.resolve()[0].ms;
//   bool clean = device.validation_enabled() && device.validation_errors() == 0;
// clang-format on
// Errors: bad selectors throw lantern::InputError (exit 2); Vulkan failures throw
// lantern::RuntimeError via VK_CHECK. The device must outlive every resource made from it.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/core/allocation_counter.h"
#include "runtime/core/debug_names.h"
#include "runtime/core/device_features.h"
#include "runtime/core/device_info.h"

namespace lantern::runtime {

class Instance;
class MemoryAllocator;
class PipelineCache;

struct DeviceOptions {
  std::string selector = "auto";  // auto|cpu|gpu|INDEX (the --device flag)
  bool validation = false;        // also on with LANTERN_VALIDATION=1 and in debug builds
  bool sync_validation = false;   // also on with LANTERN_SYNC_VALIDATION=1; implies validation
  // Where the pipeline cache lives; empty = $XDG_CACHE_HOME/lantern or ~/.cache/lantern.
  // Set LANTERN_CACHE_DIR to override it from the environment.
  std::filesystem::path cache_dir;
  bool persist_pipeline_cache = true;  // load at creation, save at destruction
  // Never hand out host pointers to DeviceLocal memory, even where it is host-visible (lavapipe,
  // integrated GPUs): uploads and readbacks then take the staging path a discrete GPU needs.
  // For tests of that path; costs a copy.
  bool force_staging = false;
  // Give the driver an AllocationCounter as the device's allocator, so live_driver_allocations()
  // can tell whether Vulkan objects leak (the soak test). Off by default: the driver's own
  // allocator is faster.
  bool count_driver_allocations = false;
  // Extra instance extensions, e.g. the window system's surface extensions.
  std::vector<const char*> instance_extensions;
  // Set for a device that presents (runtime/window/presentation.h fills both fields): enables
  // VK_KHR_swapchain and requires the chosen queue family to pass this check.
  std::function<bool(VkInstance, VkPhysicalDevice, std::uint32_t queue_family)>
      presentation_support;
};

// Device-level entry points that are extensions (or core only in 1.3), loaded once.
struct DeviceFunctions {
  PFN_vkCmdPushDescriptorSetKHR cmd_push_descriptor_set = nullptr;
  PFN_vkCmdPipelineBarrier2KHR cmd_pipeline_barrier2 = nullptr;
  PFN_vkCmdBeginRenderingKHR cmd_begin_rendering = nullptr;  // null without dynamic rendering
  PFN_vkCmdEndRenderingKHR cmd_end_rendering = nullptr;
  PFN_vkSetDebugUtilsObjectNameEXT set_object_name = nullptr;  // null without debug utils
  PFN_vkCmdBeginDebugUtilsLabelEXT cmd_begin_label = nullptr;
  PFN_vkCmdEndDebugUtilsLabelEXT cmd_end_label = nullptr;
  // VK_KHR_acceleration_structure (ray query): null unless DeviceCaps::ray_query.
  PFN_vkCreateAccelerationStructureKHR create_acceleration_structure = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroy_acceleration_structure = nullptr;
  PFN_vkGetAccelerationStructureBuildSizesKHR get_acceleration_structure_build_sizes = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR get_acceleration_structure_device_address =
      nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR cmd_build_acceleration_structures = nullptr;
};

class Device {
 public:
  // Lists every physical device (index = --device INDEX) without creating a logical device.
  static std::vector<DeviceInfo> enumerate();

  explicit Device(const DeviceOptions& options = {});
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  VkDevice handle() const { return device_; }
  VkPhysicalDevice physical_device() const { return physical_; }
  VkInstance instance() const;
  VkQueue queue() const { return queue_; }
  std::uint32_t queue_family() const { return queue_family_; }
  const DeviceInfo& info() const { return info_; }
  const DeviceCaps& caps() const { return caps_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_properties_; }
  const DeviceFunctions& fn() const { return fn_; }
  MemoryAllocator& memory() { return *memory_; }
  const MemoryAllocator& memory() const { return *memory_; }
  VkPipelineCache pipeline_cache() const;
  PipelineCache& pipeline_cache_store() { return *pipeline_cache_; }

  // Validation: enabled() is false when requested but the layer is missing (tests must fail then).
  bool validation_enabled() const;
  bool sync_validation_enabled() const;
  std::uint32_t validation_errors() const;
  std::uint32_t validation_warnings() const;
  std::uint32_t performance_warnings() const;

  // The driver's live host allocations made through this device (object scope: >= 1 per live
  // Vulkan object); throws unless DeviceOptions::count_driver_allocations was set.
  AllocationCounts live_driver_allocations() const;

  // Debug names (no-ops without VK_EXT_debug_utils).
  template <class Handle>
  void set_name(Handle handle, std::string_view name) const {
    set_object_name(ObjectTypeOf<Handle>::value, reinterpret_cast<std::uint64_t>(handle), name);
  }
  void set_object_name(VkObjectType type, std::uint64_t handle, std::string_view name) const;
  // Command-buffer labels (no-ops without VK_EXT_debug_utils); see also CommandLabel.
  void begin_label(VkCommandBuffer cmd, std::string_view name) const;
  void end_label(VkCommandBuffer cmd) const;

  // Records `record` into a fresh primary command buffer, submits it and waits for completion;
  // all device writes are then visible to host reads (mapped buffers, readbacks).
  void submit_and_wait(const std::function<void(VkCommandBuffer)>& record);
  void wait_idle() const;
  // Writes the pipeline cache to disk now (also done on destruction when persist is on).
  void save_pipeline_cache();

 private:
  const VkAllocationCallbacks* allocator() const;  // the counter's callbacks, or nullptr
  void release();  // destroys everything created so far (also for a failed constructor)

  std::unique_ptr<Instance> instance_;
  std::unique_ptr<AllocationCounter> allocations_;  // null unless count_driver_allocations
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queue_family_ = 0;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  VkFence submit_fence_ = VK_NULL_HANDLE;
  DeviceInfo info_;
  DeviceCaps caps_;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_properties_{};
  DeviceFunctions fn_;
  std::unique_ptr<MemoryAllocator> memory_;
  std::unique_ptr<PipelineCache> pipeline_cache_;
  bool persist_pipeline_cache_ = true;
};

// RAII command-buffer label: `CommandLabel label(device, cmd, "restir.initial");`
class CommandLabel {
 public:
  CommandLabel(const Device& device, VkCommandBuffer cmd, std::string_view name)
      : device_(device), cmd_(cmd) {
    device_.begin_label(cmd_, name);
  }
  ~CommandLabel() { device_.end_label(cmd_); }
  CommandLabel(const CommandLabel&) = delete;
  CommandLabel& operator=(const CommandLabel&) = delete;

 private:
  const Device& device_;
  VkCommandBuffer cmd_;
};

}  // namespace lantern::runtime
