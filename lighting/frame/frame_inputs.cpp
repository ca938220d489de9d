// SceneHandles / GBufferHandles read declarations (frame_inputs.h).
#include "lighting/frame/frame_inputs.h"

namespace lantern::lighting {

using runtime::graph::Access;

void SceneHandles::declare_reads(runtime::graph::PassBuilder& builder) const {
  for (const runtime::graph::BufferHandle& h :
       {frame_constants, vertices, indices, materials, instances, lights, alias, bvh_header,
        bvh_nodes, bvh_triangles, bvh_instances, light_previous_to_current, env_header, env_texels,
        env_marginal, env_conditional}) {
    if (h.valid()) builder.read(h, Access::StorageRead);
  }
  for (const runtime::graph::BufferHandle& h : {bvh_nodes, bvh_triangles, bvh_instances}) {
    if (h.valid()) builder.read(h, Access::UniformTexelRead);
  }
}

void GBufferHandles::declare_reads(runtime::graph::PassBuilder& builder) const {
  for (const runtime::graph::ImageHandle& h :
       {position, normal, albedo_roughness, emission_metallic, ids, motion}) {
    if (h.valid()) builder.read(h, Access::StorageRead);
  }
}

}  // namespace lantern::lighting
