// VK_KHR_acceleration_structure helpers (only on devices with DeviceCaps::ray_query): an RAII
// acceleration structure in its own buffer, triangle BLAS and instance TLAS build descriptions,
// and recording of builds. Builds are recorded on a caller's command buffer; the barrier a build
// needs before its result is read (by another build or a shader) is recorded with
// record_acceleration_structure_barrier, for one-shot setup outside the render graph (load-time
// BLAS builds, benchmarks); a build inside a frame is a graph pass (Access::AccelerationStructure*)
// whose barriers the graph derives.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "runtime/gpu/buffer.h"

namespace lantern::runtime {

class Device;

// One triangle geometry in device memory: float3 positions (stride bytes apart), optional uint32
// indices (0 address = non-indexed: three consecutive vertices per triangle).
struct TriangleGeometryDesc {
  VkDeviceAddress vertices = 0;
  VkDeviceSize vertex_stride = 12;
  std::uint32_t vertex_count = 0;
  VkDeviceAddress indices = 0;
  std::uint32_t triangle_count = 0;
  bool opaque = true;
};

// The geometry + build info of one build, kept together because the build info points into the
// geometry array (move-only for that reason).
struct AccelerationStructureBuild {
  AccelerationStructureBuild() = default;
  AccelerationStructureBuild(const AccelerationStructureBuild&) = delete;
  AccelerationStructureBuild& operator=(const AccelerationStructureBuild&) = delete;
  AccelerationStructureBuild(AccelerationStructureBuild&&) = default;
  AccelerationStructureBuild& operator=(AccelerationStructureBuild&&) = default;

  std::vector<VkAccelerationStructureGeometryKHR> geometries;
  std::vector<VkAccelerationStructureBuildRangeInfoKHR> ranges;
  VkAccelerationStructureTypeKHR type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
  VkBuildAccelerationStructureFlagsKHR flags =
      VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  // The build info (geometries pointer refreshed on each call), without dst/scratch set.
  VkAccelerationStructureBuildGeometryInfoKHR info() const;
};

// A bottom-level build over triangle geometries (one geometry per desc).
AccelerationStructureBuild triangle_blas_build(std::span<const TriangleGeometryDesc> geometries);
// A top-level build over `count` VkAccelerationStructureInstanceKHR records at `instances`
// (device address, 16-byte aligned).
AccelerationStructureBuild instance_tlas_build(VkDeviceAddress instances, std::uint32_t count);

// Memory a build needs (VkAccelerationStructureBuildSizesInfoKHR).
VkAccelerationStructureBuildSizesInfoKHR acceleration_structure_build_sizes(
    const Device& device, const AccelerationStructureBuild& build);

class AccelerationStructure {
 public:
  AccelerationStructure() = default;
  // Creates a structure of `size` bytes (build_sizes().accelerationStructureSize).
  AccelerationStructure(Device& device, VkAccelerationStructureTypeKHR type, VkDeviceSize size,
                        std::string name);
  ~AccelerationStructure();
  AccelerationStructure(AccelerationStructure&& other) noexcept;
  AccelerationStructure& operator=(AccelerationStructure&& other) noexcept;
  AccelerationStructure(const AccelerationStructure&) = delete;
  AccelerationStructure& operator=(const AccelerationStructure&) = delete;

  VkAccelerationStructureKHR handle() const { return structure_; }
  VkDeviceAddress device_address() const { return address_; }
  VkDeviceSize size() const { return storage_.size(); }
  // The buffer holding it: what a render graph imports to order builds and reads.
  const Buffer& storage() const { return storage_; }
  explicit operator bool() const { return structure_ != VK_NULL_HANDLE; }

  // Records the build of this structure from `build` using scratch memory at `scratch` (at least
  // build_scratch_size bytes, aligned to the device's scratch alignment: see ScratchBuffer).
  void record_build(VkCommandBuffer cmd, const AccelerationStructureBuild& build,
                    VkDeviceAddress scratch) const;

 private:
  void release();

  Device* device_ = nullptr;
  Buffer storage_;
  VkAccelerationStructureKHR structure_ = VK_NULL_HANDLE;
  VkDeviceAddress address_ = 0;
};

// Device-local scratch memory for builds, with its address rounded up to the device's
// minAccelerationStructureScratchOffsetAlignment. Grows on demand (reserve).
class ScratchBuffer {
 public:
  explicit ScratchBuffer(Device& device, std::string name = "as.scratch");
  // Makes room for `bytes` (reallocates when larger than the current size; the caller must not
  // have pending work that uses the old buffer).
  void reserve(VkDeviceSize bytes);
  VkDeviceAddress address() const;
  const Buffer& buffer() const { return buffer_; }

 private:
  Device* device_;
  std::string name_;
  Buffer buffer_;
  VkDeviceSize alignment_ = 256;
};

// Build writes -> later builds (reads, and scratch reuse) and compute/fragment shader reads.
void record_acceleration_structure_barrier(const Device& device, VkCommandBuffer cmd);

// The VkAccelerationStructureInstanceKHR record of one instance (row-major 3x4 transform).
VkAccelerationStructureInstanceKHR make_instance_record(const float object_to_world_rows[12],
                                                        std::uint32_t custom_index,
                                                        VkDeviceAddress blas,
                                                        std::uint8_t mask = 0xff);

}  // namespace lantern::runtime
