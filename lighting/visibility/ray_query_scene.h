// The VK_KHR_ray_query backend's scene: one BLAS per non-empty mesh of a SceneBvh (built once,
// from the same triangles the BVH holds, in the mesh's original triangle order so that a hit's
// primitive index is the mesh's triangle index) and a TLAS over its instances (custom index =
// instance index, the `instance` of shaders/lib/visibility.glsl), rebuilt from the instance
// transforms when they move. Instances of empty meshes are left out, as in the BVH's TLAS.
// Only on devices with DeviceCaps::ray_query. In the frame, GpuScene owns one: the BLASes are
// built at load, the TLAS by the graph pass scene.tlas_build from the instance records of one
// ring slot (one per frame in flight, plus one: the host never rewrites records a submitted build
// may still read).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "runtime/gpu/acceleration_structure.h"
#include "runtime/gpu/buffer.h"

namespace lantern::runtime {
class Device;
}

namespace lantern::lighting {

class SceneBvh;

class RayQueryScene {
 public:
  static constexpr std::uint32_t kInstanceSlots = 3;  // frames in flight (2) + 1

  // Uploads the triangles, then builds every BLAS and the TLAS in one blocking submit.
  RayQueryScene(runtime::Device& device, const SceneBvh& bvh);

  // Per frame: writes the instance records from bvh (its current set_instances) and rebuilds the
  // TLAS (blocking submit; call when no submitted work reads the TLAS).
  void update_instances(const SceneBvh& bvh);

  // The pieces, for callers that record builds themselves (benchmarks, a graph pass): each build
  // must be followed by runtime::record_acceleration_structure_barrier before its result is read.
  void record_blas_builds(VkCommandBuffer cmd) const;
  // Host writes of the instance records into ring slot `slot` (grows the TLAS when there are more
  // instances than it was sized for: then no submitted work may still use it).
  void write_instances(const SceneBvh& bvh, std::uint32_t slot = 0);
  // The TLAS build from the records of `slot`: reads instance_records(slot), writes the TLAS's
  // storage and the TLAS range of scratch().
  void record_tlas_build(VkCommandBuffer cmd, std::uint32_t slot = 0) const;

  VkAccelerationStructureKHR tlas() const { return tlas_.handle(); }
  const runtime::AccelerationStructure& tlas_structure() const { return tlas_; }
  const runtime::Buffer& instance_records(std::uint32_t slot) const {
    return instance_records_.at(slot);
  }
  const runtime::ScratchBuffer& scratch() const { return scratch_; }
  std::uint32_t blas_count() const { return static_cast<std::uint32_t>(blases_.size()); }

 private:
  void ensure_tlas_capacity(std::uint32_t count);

  runtime::Device* device_;
  runtime::Buffer positions_;  // float3 per triangle corner, all meshes
  std::vector<runtime::AccelerationStructureBuild> blas_builds_;
  std::vector<runtime::AccelerationStructure> blases_;
  std::vector<VkDeviceAddress> mesh_blas_;  // per mesh id: BLAS address, 0 for an empty mesh
  runtime::ScratchBuffer scratch_;
  std::vector<VkDeviceSize> blas_scratch_offsets_;  // each BLAS build gets its own scratch range
  // VkAccelerationStructureInstanceKHR per slot, host-visible.
  std::array<runtime::Buffer, kInstanceSlots> instance_records_;
  std::uint32_t instance_capacity_ = 0;
  std::uint32_t instance_count_ = 0;
  runtime::AccelerationStructure tlas_;
  VkDeviceSize blas_scratch_end_ = 0;     // scratch bytes the BLAS builds use (TLAS range follows)
  VkDeviceSize tlas_scratch_offset_ = 0;
};

}  // namespace lantern::lighting
