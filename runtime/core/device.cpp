// Device creation: pick a physical device, negotiate features, create the logical device and the
// objects every frame needs (queue, command pool, allocator, pipeline cache).
#include "runtime/core/device.h"

#include <fmt/format.h>

#include <cstdint>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "runtime/core/instance.h"
#include "runtime/core/vk_check.h"
#include "runtime/gpu/memory_allocator.h"
#include "runtime/gpu/pipeline_cache.h"

namespace lantern::runtime {
namespace {

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  std::uint32_t count = 0;
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  return devices;
}

std::vector<DeviceInfo> describe(const std::vector<VkPhysicalDevice>& devices) {
  std::vector<DeviceInfo> infos;
  for (std::uint32_t i = 0; i < devices.size(); ++i)
    infos.push_back(query_device_info(devices[i], i));
  return infos;
}

// The first queue family with graphics and compute (graphics implies transfer) that passes the
// presentation check when one is given.
std::uint32_t find_queue_family(VkInstance instance, VkPhysicalDevice device,
                                const DeviceOptions& options, std::uint32_t* timestamp_bits) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (std::uint32_t i = 0; i < count; ++i) {
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    const bool presents =
        !options.presentation_support || options.presentation_support(instance, device, i);
    if ((families[i].queueFlags & need) == need && presents) {
      *timestamp_bits = families[i].timestampValidBits;
      return i;
    }
  }
  throw RuntimeError(options.presentation_support
                         ? "Vulkan device has no queue family with graphics, compute and present "
                           "support for this window system"
                         : "Vulkan device has no queue family with both graphics and compute");
}

template <class Fn>
Fn load(VkDevice device, const char* name, const char* fallback = nullptr) {
  auto fn = vkGetDeviceProcAddr(device, name);
  if (fn == nullptr && fallback != nullptr) fn = vkGetDeviceProcAddr(device, fallback);
  return reinterpret_cast<Fn>(fn);
}

}  // namespace

std::vector<DeviceInfo> Device::enumerate() {
  Instance instance(ValidationRequest{});
  return describe(physical_devices(instance.handle()));
}

Device::Device(const DeviceOptions& options)
    : persist_pipeline_cache_(options.persist_pipeline_cache) {
  instance_ = std::make_unique<Instance>(
      resolve_validation_request(options.validation, options.sync_validation),
      options.instance_extensions);
  const auto devices = physical_devices(instance_->handle());
  const auto infos = describe(devices);
  const std::uint32_t index = select_device(infos, options.selector);
  physical_ = devices[index];
  info_ = infos[index];
  vkGetPhysicalDeviceProperties(physical_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_properties_);

  std::uint32_t timestamp_bits = 0;
  queue_family_ = find_queue_family(instance_->handle(), physical_, options, &timestamp_bits);
  FeatureNegotiation features(physical_, timestamp_bits);
  caps_ = features.caps();
  caps_.debug_utils = instance_->debug_utils();

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = features.chain();
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  std::vector<const char*> extensions = features.extensions();
  if (options.presentation_support) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  if (options.count_driver_allocations) allocations_ = std::make_unique<AllocationCounter>();
  VK_CHECK(vkCreateDevice(physical_, &info, allocator(), &device_));
  try {
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

    const bool core13 = caps_.api_version >= VK_API_VERSION_1_3;
    fn_.cmd_push_descriptor_set =
        load<PFN_vkCmdPushDescriptorSetKHR>(device_, "vkCmdPushDescriptorSetKHR");
    fn_.cmd_pipeline_barrier2 = load<PFN_vkCmdPipelineBarrier2KHR>(
        device_, core13 ? "vkCmdPipelineBarrier2" : "vkCmdPipelineBarrier2KHR");
    if (caps_.dynamic_rendering) {
      fn_.cmd_begin_rendering = load<PFN_vkCmdBeginRenderingKHR>(
          device_, core13 ? "vkCmdBeginRendering" : "vkCmdBeginRenderingKHR");
      fn_.cmd_end_rendering = load<PFN_vkCmdEndRenderingKHR>(
          device_, core13 ? "vkCmdEndRendering" : "vkCmdEndRenderingKHR");
    }
    if (caps_.debug_utils) {
      VkInstance inst = instance_->handle();
      fn_.set_object_name = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
          vkGetInstanceProcAddr(inst, "vkSetDebugUtilsObjectNameEXT"));
      fn_.cmd_begin_label = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
          vkGetInstanceProcAddr(inst, "vkCmdBeginDebugUtilsLabelEXT"));
      fn_.cmd_end_label = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
          vkGetInstanceProcAddr(inst, "vkCmdEndDebugUtilsLabelEXT"));
    }
    if (fn_.cmd_push_descriptor_set == nullptr || fn_.cmd_pipeline_barrier2 == nullptr)
      throw RuntimeError(
          "Vulkan driver did not return vkCmdPushDescriptorSetKHR / vkCmdPipelineBarrier2");
    if (caps_.ray_query) {
      fn_.create_acceleration_structure =
          load<PFN_vkCreateAccelerationStructureKHR>(device_, "vkCreateAccelerationStructureKHR");
      fn_.destroy_acceleration_structure =
          load<PFN_vkDestroyAccelerationStructureKHR>(device_, "vkDestroyAccelerationStructureKHR");
      fn_.get_acceleration_structure_build_sizes =
          load<PFN_vkGetAccelerationStructureBuildSizesKHR>(
              device_, "vkGetAccelerationStructureBuildSizesKHR");
      fn_.get_acceleration_structure_device_address =
          load<PFN_vkGetAccelerationStructureDeviceAddressKHR>(
              device_, "vkGetAccelerationStructureDeviceAddressKHR");
      fn_.cmd_build_acceleration_structures = load<PFN_vkCmdBuildAccelerationStructuresKHR>(
          device_, "vkCmdBuildAccelerationStructuresKHR");
      if (fn_.create_acceleration_structure == nullptr ||
          fn_.destroy_acceleration_structure == nullptr ||
          fn_.get_acceleration_structure_build_sizes == nullptr ||
          fn_.get_acceleration_structure_device_address == nullptr ||
          fn_.cmd_build_acceleration_structures == nullptr)
        throw RuntimeError(
            "Vulkan driver reports VK_KHR_acceleration_structure but did not return its entry "
            "points");
    }

    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags =
        VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = queue_family_;
    VK_CHECK(vkCreateCommandPool(device_, &pool_info, nullptr, &command_pool_));
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(device_, &fence_info, nullptr, &submit_fence_));

    memory_ = std::make_unique<MemoryAllocator>(
        device_, memory_properties_,
        MemoryAllocator::Options{.device_address = caps_.buffer_device_address,
                                 .map_device_local = !options.force_staging});
    pipeline_cache_ = std::make_unique<PipelineCache>(device_, properties_, options.cache_dir,
                                                      options.persist_pipeline_cache);
    set_name(queue_, "lantern.queue");
    set_name(command_pool_, "lantern.one_shot_pool");

    log::info(
        "Vulkan device {}: {} ({}, Vulkan {}, {}); ray query {}, descriptor indexing {}, "
        "validation "
        "{}",
        info_.index, info_.name, info_.type, info_.api_version, info_.driver,
        caps_.ray_query ? "yes" : "no", caps_.descriptor_indexing ? "yes" : "no",
        instance_->sync_validation_enabled() ? "on (+sync)"
        : instance_->validation_enabled()    ? "on"
                                             : "off");
  } catch (...) {
    release();  // the destructor does not run for a half-built object
    throw;
  }
}

Device::~Device() {
  if (device_ != VK_NULL_HANDLE) vkDeviceWaitIdle(device_);
  if (pipeline_cache_ && persist_pipeline_cache_) pipeline_cache_->save();
  release();
}

void Device::release() {
  pipeline_cache_.reset();
  memory_.reset();
  if (submit_fence_ != VK_NULL_HANDLE) vkDestroyFence(device_, submit_fence_, nullptr);
  if (command_pool_ != VK_NULL_HANDLE) vkDestroyCommandPool(device_, command_pool_, nullptr);
  if (device_ != VK_NULL_HANDLE) vkDestroyDevice(device_, allocator());
  device_ = VK_NULL_HANDLE;
}

const VkAllocationCallbacks* Device::allocator() const {
  return allocations_ ? allocations_->callbacks() : nullptr;
}
AllocationCounts Device::live_driver_allocations() const {
  if (!allocations_)
    throw RuntimeError("live_driver_allocations() needs DeviceOptions::count_driver_allocations");
  return allocations_->live();
}
VkInstance Device::instance() const {
  return instance_->handle();
}
VkPipelineCache Device::pipeline_cache() const {
  return pipeline_cache_->handle();
}
bool Device::validation_enabled() const {
  return instance_->validation_enabled();
}
bool Device::sync_validation_enabled() const {
  return instance_->sync_validation_enabled();
}
std::uint32_t Device::validation_errors() const {
  return instance_->counters().errors.load();
}
std::uint32_t Device::validation_warnings() const {
  return instance_->counters().warnings.load();
}
std::uint32_t Device::performance_warnings() const {
  return instance_->counters().performance_warnings.load();
}

void Device::set_object_name(VkObjectType type, std::uint64_t handle, std::string_view name) const {
  if (fn_.set_object_name == nullptr || handle == 0) return;
  const std::string text(name);
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = text.c_str();
  VK_CHECK(fn_.set_object_name(device_, &info));
}

void Device::begin_label(VkCommandBuffer cmd, std::string_view name) const {
  if (fn_.cmd_begin_label == nullptr) return;
  const std::string text(name);
  VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
  label.pLabelName = text.c_str();
  fn_.cmd_begin_label(cmd, &label);
}

void Device::end_label(VkCommandBuffer cmd) const {
  if (fn_.cmd_end_label != nullptr) fn_.cmd_end_label(cmd);
}

void Device::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = command_pool_;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateCommandBuffers(device_, &alloc, &cmd));
  struct FreeOnExit {
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    ~FreeOnExit() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
  } guard{device_, command_pool_, cmd};

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  // The caller reads results on the host after this returns: make every device write visible to
  // host reads (a fence alone does not; see the spec's "Host Write Ordering Guarantees").
  VkMemoryBarrier2 to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  to_host.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  to_host.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  to_host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
  to_host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &to_host;
  fn_.cmd_pipeline_barrier2(cmd, &dependency);
  VK_CHECK(vkEndCommandBuffer(cmd));

  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  VK_CHECK(vkResetFences(device_, 1, &submit_fence_));
  VK_CHECK(vkQueueSubmit(queue_, 1, &submit, submit_fence_));
  VK_CHECK(vkWaitForFences(device_, 1, &submit_fence_, VK_TRUE, UINT64_MAX));
}

void Device::wait_idle() const {
  VK_CHECK(vkDeviceWaitIdle(device_));
}

void Device::save_pipeline_cache() {
  if (const std::size_t bytes = pipeline_cache_->save(); bytes > 0)
    log::debug("pipeline cache: {} bytes written to {}", bytes, pipeline_cache_->file().string());
}

}  // namespace lantern::runtime
