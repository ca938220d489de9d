// scene.upload: SceneData -> device-local storage buffers (gpu_scene.h).
#include "lighting/scene/gpu_scene.h"

#include <span>
#include <string>
#include <vector>

#include "runtime/core/device.h"
#include "runtime/gpu/transfer.h"

namespace lantern::lighting {
namespace {

// A storage buffer holding `values` (one zeroed element when empty: Vulkan has no empty buffers).
template <class T>
runtime::Buffer make_storage(runtime::Device& device, const std::vector<T>& values,
                             const std::string& name) {
  std::vector<T> data = values;
  if (data.empty()) data.push_back(T{});
  runtime::Buffer buffer(device, {.size = data.size() * sizeof(T),
                                  .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  .memory = runtime::MemoryUsage::DeviceLocal,
                                  .name = name});
  runtime::upload_buffer(device, buffer, std::span<const T>(data));
  return buffer;
}

}  // namespace

GpuScene::GpuScene(runtime::Device& device, const SceneData& scene)
    : bvh_header_(make_storage(device, std::vector{scene.bvh.header()}, "scene.bvh_header")),
      bvh_nodes_(make_storage(device, scene.bvh.nodes(), "scene.bvh_nodes")),
      bvh_triangles_(make_storage(device, scene.bvh.triangles(), "scene.bvh_triangles")),
      bvh_instances_(make_storage(device, scene.bvh.instances(), "scene.bvh_instances")),
      vertices_(make_storage(device, scene.vertices, "scene.vertices")),
      indices_(make_storage(device, scene.indices, "scene.indices")),
      materials_(make_storage(device, scene.materials, "scene.materials")),
      instances_(make_storage(device, scene.instances, "scene.instances")),
      lights_(make_storage(device, scene.lights.lights(), "scene.lights")),
      alias_(make_storage(device, scene.lights.alias_table().entries(), "scene.light_alias")),
      light_count_(
          scene.lights.has_power() ? static_cast<std::uint32_t>(scene.lights.lights().size()) : 0u),
      instance_count_(static_cast<std::uint32_t>(scene.instances.size())),
      scene_radius_(scene.scene_radius()) {}

void GpuScene::bind(runtime::Bindings& bindings) const {
  bindings.buffer("BvhHeaderBuffer", bvh_header_)
      .buffer("BvhNodeBuffer", bvh_nodes_)
      .buffer("BvhTriangleBuffer", bvh_triangles_)
      .buffer("BvhInstanceBuffer", bvh_instances_)
      .buffer("scene_vertices", vertices_)
      .buffer("scene_indices", indices_)
      .buffer("scene_materials", materials_)
      .buffer("scene_instances", instances_)
      .buffer("scene_lights", lights_)
      .buffer("light_alias", alias_);
}

std::uint64_t GpuScene::bytes() const {
  std::uint64_t total = 0;
  for (const runtime::Buffer* b :
       {&bvh_header_, &bvh_nodes_, &bvh_triangles_, &bvh_instances_, &vertices_, &indices_,
        &materials_, &instances_, &lights_, &alias_}) {
    total += b->size();
  }
  return total;
}

}  // namespace lantern::lighting
