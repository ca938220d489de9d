// Dispatch shape and name-based binding helpers of the restir.* passes.
#include "lighting/restir/restir_pass_common.h"

#include "engine/core/error.h"
#include "lighting/frame/tile_order.h"
#include "lighting/scene/gpu_scene.h"
#include "shared/restir.h"

namespace lantern::lighting::restir_detail {

std::uint32_t tile_count(std::uint32_t width, std::uint32_t height) {
  return lighting::tile_count(width, height, gpu::kRestirTileSize);
}

void bind_buffer(runtime::Bindings& b, const runtime::graph::PassContext& ctx,
                 std::string_view name, runtime::graph::BufferHandle h) {
  b.buffer(name, ctx.buffer(h), 0, VK_WHOLE_SIZE);
}

void bind_image(runtime::Bindings& b, const runtime::graph::PassContext& ctx,
                std::string_view name, runtime::graph::ImageHandle h) {
  b.image_view(name, ctx.view(h), VK_IMAGE_LAYOUT_GENERAL);
}

void bind_visibility(runtime::Bindings& b, const runtime::graph::PassContext& ctx,
                     const SceneHandles& handles, const GpuScene* scene) {
  if (b.has("bvh_node_texels")) {
    if (scene == nullptr) {
      throw RuntimeError("restir: the BVH texel views need the frame's GpuScene (FrameInputs::scene)");
    }
    // Every scene name the pipeline declares, texel views included; the graph handles bound
    // after this (the same buffers) take precedence for the storage buffers.
    scene->bind(b);
  } else {
    bind_buffer(b, ctx, "BvhNodeBuffer", handles.bvh_nodes);
    bind_buffer(b, ctx, "BvhTriangleBuffer", handles.bvh_triangles);
    bind_buffer(b, ctx, "BvhInstanceBuffer", handles.bvh_instances);
  }
  bind_buffer(b, ctx, "BvhHeaderBuffer", handles.bvh_header);
}

void declare_environment_reads(runtime::graph::PassBuilder& b, const SceneHandles& handles) {
  for (runtime::graph::BufferHandle h :
       {handles.env_header, handles.env_texels, handles.env_marginal, handles.env_conditional}) {
    b.read(h, runtime::graph::Access::StorageRead);
  }
}

void bind_environment(runtime::Bindings& b, const runtime::graph::PassContext& ctx,
                      const SceneHandles& handles) {
  bind_buffer(b, ctx, "env_header", handles.env_header);
  bind_buffer(b, ctx, "env_texels", handles.env_texels);
  bind_buffer(b, ctx, "env_marginal", handles.env_marginal);
  bind_buffer(b, ctx, "env_conditional", handles.env_conditional);
}

}  // namespace lantern::lighting::restir_detail
