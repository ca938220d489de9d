// Acceleration structures (acceleration_structure.h). The extension's entry points come from
// the device's DeviceFunctions (loaded once when the device is created).
#include "runtime/gpu/acceleration_structure.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <utility>

#include "engine/core/error.h"
#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"

namespace lantern::runtime {
namespace {

// The entry points, loaded once with the device (DeviceFunctions); a device without ray query
// has none.
const DeviceFunctions& functions(const Device& device) {
  if (!device.caps().ray_query || device.fn().create_acceleration_structure == nullptr)
    throw RuntimeError(
        "acceleration structures need VK_KHR_acceleration_structure + VK_KHR_ray_query, which this "
        "device lacks");
  return device.fn();
}

std::vector<std::uint32_t> primitive_counts(const AccelerationStructureBuild& build) {
  std::vector<std::uint32_t> counts;
  for (const auto& r : build.ranges) counts.push_back(r.primitiveCount);
  return counts;
}

}  // namespace

VkAccelerationStructureBuildGeometryInfoKHR AccelerationStructureBuild::info() const {
  VkAccelerationStructureBuildGeometryInfoKHR info{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  info.type = type;
  info.flags = flags;
  info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  info.geometryCount = static_cast<std::uint32_t>(geometries.size());
  info.pGeometries = geometries.data();
  return info;
}

AccelerationStructureBuild triangle_blas_build(std::span<const TriangleGeometryDesc> geometries) {
  AccelerationStructureBuild build;
  build.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
  for (const TriangleGeometryDesc& g : geometries) {
    VkAccelerationStructureGeometryKHR geometry{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    geometry.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
    geometry.flags = g.opaque ? VK_GEOMETRY_OPAQUE_BIT_KHR : 0;
    auto& t = geometry.geometry.triangles;
    t.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
    t.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
    t.vertexData.deviceAddress = g.vertices;
    t.vertexStride = g.vertex_stride;
    t.maxVertex = g.vertex_count == 0 ? 0 : g.vertex_count - 1;
    t.indexType = g.indices != 0 ? VK_INDEX_TYPE_UINT32 : VK_INDEX_TYPE_NONE_KHR;
    t.indexData.deviceAddress = g.indices;
    build.geometries.push_back(geometry);
    build.ranges.push_back({g.triangle_count, 0, 0, 0});
  }
  return build;
}

AccelerationStructureBuild instance_tlas_build(VkDeviceAddress instances, std::uint32_t count) {
  AccelerationStructureBuild build;
  build.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  VkAccelerationStructureGeometryKHR geometry{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geometry.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  geometry.geometry.instances.sType =
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  geometry.geometry.instances.arrayOfPointers = VK_FALSE;
  geometry.geometry.instances.data.deviceAddress = instances;
  build.geometries.push_back(geometry);
  build.ranges.push_back({count, 0, 0, 0});
  return build;
}

VkAccelerationStructureBuildSizesInfoKHR acceleration_structure_build_sizes(
    const Device& device, const AccelerationStructureBuild& build) {
  const DeviceFunctions& fn = functions(device);
  VkAccelerationStructureBuildGeometryInfoKHR info = build.info();
  const std::vector<std::uint32_t> counts = primitive_counts(build);
  VkAccelerationStructureBuildSizesInfoKHR sizes{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  fn.get_acceleration_structure_build_sizes(device.handle(),
                                            VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info,
                                            counts.data(), &sizes);
  return sizes;
}

AccelerationStructure::AccelerationStructure(Device& device, VkAccelerationStructureTypeKHR type,
                                             VkDeviceSize size, std::string name)
    : device_(&device),
      storage_(device, {.size = size,
                        .usage = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR |
                                 VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                        .memory = MemoryUsage::DeviceLocal,
                        .name = name + ".storage"}) {
  const DeviceFunctions& fn = functions(device);
  VkAccelerationStructureCreateInfoKHR info{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  info.buffer = storage_.handle();
  info.offset = 0;
  info.size = size;
  info.type = type;
  VK_CHECK(fn.create_acceleration_structure(device.handle(), &info, nullptr, &structure_));
  VkAccelerationStructureDeviceAddressInfoKHR address{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  address.accelerationStructure = structure_;
  address_ = fn.get_acceleration_structure_device_address(device.handle(), &address);
  device.set_name(structure_, name);
}

AccelerationStructure::~AccelerationStructure() {
  release();
}

AccelerationStructure::AccelerationStructure(AccelerationStructure&& other) noexcept {
  *this = std::move(other);
}

AccelerationStructure& AccelerationStructure::operator=(AccelerationStructure&& other) noexcept {
  if (this != &other) {
    release();
    device_ = std::exchange(other.device_, nullptr);
    storage_ = std::move(other.storage_);
    structure_ = std::exchange(other.structure_, VK_NULL_HANDLE);
    address_ = std::exchange(other.address_, 0);
  }
  return *this;
}

void AccelerationStructure::release() {
  if (structure_ == VK_NULL_HANDLE) return;
  functions(*device_).destroy_acceleration_structure(device_->handle(), structure_, nullptr);
  structure_ = VK_NULL_HANDLE;
}

void AccelerationStructure::record_build(VkCommandBuffer cmd,
                                         const AccelerationStructureBuild& build,
                                         VkDeviceAddress scratch) const {
  const DeviceFunctions& fn = functions(*device_);
  VkAccelerationStructureBuildGeometryInfoKHR info = build.info();
  info.dstAccelerationStructure = structure_;
  info.scratchData.deviceAddress = scratch;
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = build.ranges.data();
  fn.cmd_build_acceleration_structures(cmd, 1, &info, &ranges);
}

ScratchBuffer::ScratchBuffer(Device& device, std::string name)
    : device_(&device), name_(std::move(name)) {
  VkPhysicalDeviceAccelerationStructurePropertiesKHR as_props{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &as_props;
  vkGetPhysicalDeviceProperties2(device.physical_device(), &props);
  alignment_ = std::max<VkDeviceSize>(as_props.minAccelerationStructureScratchOffsetAlignment, 1);
}

void ScratchBuffer::reserve(VkDeviceSize bytes) {
  const VkDeviceSize needed = bytes + alignment_;
  if (buffer_ && buffer_.size() >= needed) return;
  buffer_ = Buffer(*device_, {.size = needed,
                              .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                       VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                              .memory = MemoryUsage::DeviceLocal,
                              .name = name_});
}

VkDeviceAddress ScratchBuffer::address() const {
  if (!buffer_) throw RuntimeError(fmt::format("{}: reserve() before address()", name_));
  return (buffer_.device_address() + alignment_ - 1) / alignment_ * alignment_;
}

void record_acceleration_structure_barrier(const Device& device, VkCommandBuffer cmd) {
  VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  barrier.srcStageMask = VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR;
  barrier.srcAccessMask = VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
  barrier.dstStageMask = VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR |
                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                         VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
  barrier.dstAccessMask = VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR |
                          VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &barrier;
  device.fn().cmd_pipeline_barrier2(cmd, &dependency);
}

VkAccelerationStructureInstanceKHR make_instance_record(const float object_to_world_rows[12],
                                                        std::uint32_t custom_index,
                                                        VkDeviceAddress blas, std::uint8_t mask) {
  if (custom_index >= (1u << 24))
    throw RuntimeError(fmt::format("TLAS instance index {} exceeds 24 bits", custom_index));
  VkAccelerationStructureInstanceKHR record{};
  std::memcpy(record.transform.matrix, object_to_world_rows, sizeof(record.transform.matrix));
  record.instanceCustomIndex = custom_index;
  record.mask = mask;
  record.instanceShaderBindingTableRecordOffset = 0;
  record.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
  record.accelerationStructureReference = blas;
  return record;
}

}  // namespace lantern::runtime
