// Visibility resources and their binding (visibility_scene.h).
#include "lighting/visibility/visibility_scene.h"

#include <fmt/format.h>

#include <span>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "lighting/bvh/scene_bvh.h"
#include "lighting/visibility/ray_query_scene.h"
#include "runtime/core/device.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/pipeline.h"
#include "runtime/gpu/transfer.h"

namespace lantern::lighting {
namespace {

// Uploads `values` (one zeroed element when empty) into `buffer`, reallocating it (and its view,
// when `view` is given) when the size changed.
template <class T>
void upload_array(runtime::Device& device, const std::vector<T>& values, const std::string& name,
                  runtime::Buffer& buffer, runtime::BufferView* view) {
  std::vector<T> data = values;
  if (data.empty()) data.push_back(T{});
  const VkDeviceSize size = data.size() * sizeof(T);
  if (!buffer || buffer.size() != size) {
    buffer = runtime::Buffer(device, {.size = size,
                                      .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                               VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                                      .memory = runtime::MemoryUsage::DeviceLocal,
                                      .name = name});
    if (view != nullptr)
      *view = runtime::BufferView(device, buffer, VK_FORMAT_R32G32B32A32_UINT, name + ".texels");
  }
  runtime::upload_buffer(device, buffer, std::span<const T>(data));
}

}  // namespace

VisibilityScene::VisibilityScene(runtime::Device& device, const SceneBvh& bvh,
                                 VisibilityBackend backend)
    : device_(&device), backend_(backend) {
  if (backend_ == VisibilityBackend::RayQuery && !device.caps().ray_query)
    throw InputError(fmt::format(
        "visibility backend 'rayquery' needs VK_KHR_ray_query and VK_KHR_acceleration_structure, "
        "which device '{}' lacks (see `lantern devices`); use 'bvh'",
        device.info().name));
  upload_bvh(bvh);
  if (backend_ == VisibilityBackend::RayQuery)
    ray_query_ = std::make_unique<RayQueryScene>(device, bvh);
}

VisibilityScene::~VisibilityScene() = default;
VisibilityScene::VisibilityScene(VisibilityScene&&) noexcept = default;
VisibilityScene& VisibilityScene::operator=(VisibilityScene&&) noexcept = default;

void VisibilityScene::upload_bvh(const SceneBvh& bvh) {
  upload_array(*device_, std::vector{bvh.header()}, "visibility.bvh_header", header_, nullptr);
  upload_array(*device_, bvh.nodes(), "visibility.bvh_nodes", nodes_, &node_view_);
  upload_array(*device_, bvh.triangles(), "visibility.bvh_triangles", triangles_, &triangle_view_);
  upload_array(*device_, bvh.instances(), "visibility.bvh_instances", instances_, &instance_view_);
}

void VisibilityScene::update(const SceneBvh& bvh) {
  upload_bvh(bvh);
  if (ray_query_) ray_query_->update_instances(bvh);
}

void VisibilityScene::bind(runtime::Bindings& bindings) const {
  if (bindings.has("scene_tlas")) {
    if (!ray_query_)
      throw RuntimeError(fmt::format(
          "pipeline '{}' was compiled for ray-query visibility but the scene's backend is '{}': "
          "load it with visibility_variant(backend())",
          bindings.pipeline().name(), visibility_backend_name(backend_)));
    bindings.acceleration_structure("scene_tlas", ray_query_->tlas());
    return;
  }
  bindings.buffer("BvhHeaderBuffer", header_);
  if (bindings.has("bvh_node_texels")) {
    bindings.texel_buffer("bvh_node_texels", node_view_.handle())
        .texel_buffer("bvh_triangle_texels", triangle_view_.handle())
        .texel_buffer("bvh_instance_texels", instance_view_.handle());
  } else {
    bindings.buffer("BvhNodeBuffer", nodes_)
        .buffer("BvhTriangleBuffer", triangles_)
        .buffer("BvhInstanceBuffer", instances_);
  }
}

}  // namespace lantern::lighting
