// Ray-query scene: BLAS per mesh, TLAS per frame (ray_query_scene.h).
#include "lighting/visibility/ray_query_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <glm/glm.hpp>
#include <span>

#include "lighting/bvh/scene_bvh.h"
#include "runtime/core/device.h"
#include "runtime/gpu/transfer.h"

namespace lantern::lighting {
namespace {

VkDeviceSize align_up(VkDeviceSize value, VkDeviceSize alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

// Scratch ranges are placed at multiples of this (>= any device's scratch alignment we meet).
constexpr VkDeviceSize kScratchAlignment = 256;

}  // namespace

RayQueryScene::RayQueryScene(runtime::Device& device, const SceneBvh& bvh)
    : device_(&device), scratch_(device, "visibility.as_scratch") {
  // Corner positions of every triangle of every mesh, in each mesh's original triangle order
  // (BvhTriangle holds v0 and the two edges in leaf order, v0.w = original index).
  std::vector<glm::vec3> positions;
  std::vector<std::size_t> mesh_first(bvh.mesh_count(), 0);
  for (std::size_t m = 0; m < bvh.mesh_count(); ++m) {
    const auto& tris = bvh.mesh(static_cast<std::uint32_t>(m)).triangles();
    mesh_first[m] = positions.size();
    positions.resize(positions.size() + 3 * tris.size());
    for (const gpu::BvhTriangle& t : tris) {
      const std::size_t o = mesh_first[m] + 3 * glm::floatBitsToUint(t.v0.w);
      const glm::vec3 v0(t.v0);
      positions[o] = v0;
      positions[o + 1] = v0 + glm::vec3(t.e1);
      positions[o + 2] = v0 + glm::vec3(t.e2);
    }
  }
  if (positions.empty()) positions.emplace_back(0.0f);
  positions_ = runtime::Buffer(
      device, {.size = positions.size() * sizeof(glm::vec3),
               .usage = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
                        VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
               .memory = runtime::MemoryUsage::DeviceLocal,
               .name = "visibility.blas_positions"});
  runtime::upload_buffer(device, positions_, std::span<const glm::vec3>(positions));

  VkDeviceSize scratch_total = 0;
  mesh_blas_.assign(bvh.mesh_count(), 0);
  for (std::size_t m = 0; m < bvh.mesh_count(); ++m) {
    const std::size_t count = bvh.mesh(static_cast<std::uint32_t>(m)).triangle_count();
    if (count == 0) continue;
    runtime::TriangleGeometryDesc geometry;
    geometry.vertices = positions_.device_address() + mesh_first[m] * sizeof(glm::vec3);
    geometry.vertex_stride = sizeof(glm::vec3);
    geometry.vertex_count = static_cast<std::uint32_t>(3 * count);
    geometry.triangle_count = static_cast<std::uint32_t>(count);
    runtime::AccelerationStructureBuild build =
        runtime::triangle_blas_build(std::span(&geometry, 1));
    const auto sizes = runtime::acceleration_structure_build_sizes(device, build);
    blases_.emplace_back(device, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
                         sizes.accelerationStructureSize, fmt::format("visibility.blas{}", m));
    mesh_blas_[m] = blases_.back().device_address();
    blas_scratch_offsets_.push_back(scratch_total);
    scratch_total += align_up(sizes.buildScratchSize, kScratchAlignment);
    blas_builds_.push_back(std::move(build));
  }
  blas_scratch_end_ = scratch_total;
  write_instances(bvh);  // reserves the scratch for the BLAS ranges and the TLAS behind them
  device.submit_and_wait([&](VkCommandBuffer cmd) {
    record_blas_builds(cmd);
    runtime::record_acceleration_structure_barrier(device, cmd);
    record_tlas_build(cmd);
    runtime::record_acceleration_structure_barrier(device, cmd);
  });
}

void RayQueryScene::record_blas_builds(VkCommandBuffer cmd) const {
  for (std::size_t i = 0; i < blases_.size(); ++i)
    blases_[i].record_build(cmd, blas_builds_[i], scratch_.address() + blas_scratch_offsets_[i]);
}

void RayQueryScene::ensure_tlas_capacity(std::uint32_t count) {
  if (count <= instance_capacity_ && tlas_) return;
  const std::uint32_t capacity = std::max<std::uint32_t>({count, 2 * instance_capacity_, 1u});
  for (std::uint32_t slot = 0; slot < kInstanceSlots; ++slot) {
    instance_records_[slot] = runtime::Buffer(
        *device_, {.size = capacity * sizeof(VkAccelerationStructureInstanceKHR),
                   .usage = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
                            VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                   .memory = runtime::MemoryUsage::Upload,
                   .name = fmt::format("scene.tlas_instances.{}", slot)});
  }
  const runtime::AccelerationStructureBuild build =
      runtime::instance_tlas_build(instance_records_[0].device_address(), capacity);
  const auto sizes = runtime::acceleration_structure_build_sizes(*device_, build);
  tlas_ = runtime::AccelerationStructure(*device_, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
                                         sizes.accelerationStructureSize, "scene.tlas");
  // The TLAS scratch follows the BLAS ranges, so a TLAS rebuild never overlaps a BLAS build's.
  tlas_scratch_offset_ = blas_scratch_end_;
  scratch_.reserve(blas_scratch_end_ + align_up(sizes.buildScratchSize, kScratchAlignment));
  instance_capacity_ = capacity;
}

void RayQueryScene::write_instances(const SceneBvh& bvh, std::uint32_t slot) {
  std::vector<VkAccelerationStructureInstanceKHR> records;
  // The instances as placed (not SceneBvh's merged record: ray query has its own TLAS per mesh).
  const auto& instances = bvh.instances();
  for (std::size_t i = 0; i < bvh.instance_count(); ++i) {
    const VkDeviceAddress blas = mesh_blas_.at(bvh.instance_mesh(i));
    if (blas == 0) continue;
    const glm::mat4& m = instances[i].object_to_world;
    float rows[12];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) rows[4 * r + c] = m[c][r];
    records.push_back(runtime::make_instance_record(rows, static_cast<std::uint32_t>(i), blas));
    // Alpha-tested instances report candidate hits, which the shaders' query loop confirms
    // where the material is not cut out (shaders/lib/visibility.glsl).
    if ((instances[i].flags & gpu::kBvhInstanceAlphaTested) != 0u)
      records.back().flags |= VK_GEOMETRY_INSTANCE_FORCE_NO_OPAQUE_BIT_KHR;
  }
  ensure_tlas_capacity(static_cast<std::uint32_t>(records.size()));
  if (!records.empty())
    std::memcpy(instance_records_.at(slot).mapped(), records.data(),
                records.size() * sizeof(VkAccelerationStructureInstanceKHR));
  instance_count_ = static_cast<std::uint32_t>(records.size());
}

void RayQueryScene::record_tlas_build(VkCommandBuffer cmd, std::uint32_t slot) const {
  const runtime::AccelerationStructureBuild build =
      runtime::instance_tlas_build(instance_records_.at(slot).device_address(), instance_count_);
  tlas_.record_build(cmd, build, scratch_.address() + tlas_scratch_offset_);
}

void RayQueryScene::update_instances(const SceneBvh& bvh) {
  write_instances(bvh);
  device_->submit_and_wait([&](VkCommandBuffer cmd) {
    record_tlas_build(cmd);
    runtime::record_acceleration_structure_barrier(*device_, cmd);
  });
}

}  // namespace lantern::lighting
