// The scene buffer table and SceneHandles' read declarations and binding (scene_buffers.h).
#include "lighting/scene/scene_buffers.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "lighting/scene/scene_data.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/pipeline.h"
#include "runtime/graph/pass_context.h"
#include "runtime/graph/render_graph.h"

namespace lantern::lighting {
namespace {

template <class T>
std::span<const std::byte> bytes_of(const std::vector<T>& v) {
  return std::as_bytes(std::span<const T>(v));
}
template <class T>
std::span<const std::byte> bytes_of_one(const T* value) {
  return std::as_bytes(std::span<const T>(value, 1));
}

using Sources = SceneBufferSources;
constexpr SceneResourceKind kBuffer = SceneResourceKind::Buffer;

}  // namespace

// clang-format off
constexpr std::array<SceneBufferRow, gpu::kSceneBufferCount> kSceneBuffers = {{
    {gpu::kSceneFrameConstants, "scene.frame_constants", "frame_constants", nullptr, false,
     [](const Sources& s) { return bytes_of_one(s.frame_constants); }, kBuffer},
    {gpu::kSceneVertices, "scene.vertices", "scene_vertices", nullptr, true,
     [](const Sources& s) { return bytes_of(s.data->vertices); }, kBuffer},
    {gpu::kSceneIndices, "scene.indices", "scene_indices", nullptr, true,
     [](const Sources& s) { return bytes_of(s.data->indices); }, kBuffer},
    {gpu::kSceneMaterials, "scene.materials", "scene_materials", nullptr, true,
     [](const Sources& s) { return bytes_of(s.data->materials); }, kBuffer},
    {gpu::kSceneInstances, "scene.instances", "scene_instances", nullptr, false,
     [](const Sources& s) { return bytes_of(s.data->instances); }, kBuffer},
    {gpu::kSceneLights, "scene.lights", "scene_lights", "scene_light_texels", false,
     [](const Sources& s) { return bytes_of(s.data->lights.lights()); }, kBuffer},
    {gpu::kSceneLightAlias, "scene.light_alias", "light_alias", "light_alias_texels", false,
     [](const Sources& s) { return bytes_of(s.data->lights.alias_entries()); }, kBuffer},
    {gpu::kSceneLightPreviousToCurrent, "scene.light_previous_to_current",
     "light_previous_to_current", nullptr, false,
     [](const Sources& s) { return bytes_of(*s.light_previous_to_current); }, kBuffer},
    {gpu::kSceneBvhHeader, "scene.bvh_header", "BvhHeaderBuffer", nullptr, false,
     [](const Sources& s) { return bytes_of_one(&s.data->bvh.header()); }, kBuffer},
    {gpu::kSceneBvhNodes, "scene.bvh_nodes", "BvhNodeBuffer", "bvh_node_texels", false,
     [](const Sources& s) { return bytes_of(s.data->bvh.nodes()); }, kBuffer},
    // Written again when a fixed instance moves out of the merged tree (SceneBvh::blas_generation).
    {gpu::kSceneBvhTriangles, "scene.bvh_triangles", "BvhTriangleBuffer", "bvh_triangle_texels",
     false, [](const Sources& s) { return bytes_of(s.data->bvh.triangles()); }, kBuffer},
    {gpu::kSceneBvhInstances, "scene.bvh_instances", "BvhInstanceBuffer", "bvh_instance_texels",
     false, [](const Sources& s) { return bytes_of(s.data->bvh.instances()); }, kBuffer},
    {gpu::kSceneEnvHeader, "scene.env_header", "env_header", nullptr, false,
     [](const Sources& s) { return bytes_of_one(s.env_header); }, kBuffer},
    {gpu::kSceneEnvTexels, "scene.env_texels", "env_texels", nullptr, true,
     [](const Sources& s) { return s.env_texels; }, kBuffer},
    {gpu::kSceneEnvMarginal, "scene.env_marginal", "env_marginal", nullptr, true,
     [](const Sources& s) { return s.env_marginal; }, kBuffer},
    {gpu::kSceneEnvConditional, "scene.env_conditional", "env_conditional", nullptr, true,
     [](const Sources& s) { return s.env_conditional; }, kBuffer},
    {gpu::kSceneTextures, "scene.textures", "scene_textures", nullptr, true,
     [](const Sources& s) { return bytes_of(s.data->textures.records()); }, kBuffer},
    {gpu::kSceneTexels, "scene.texels", "scene_texels", nullptr, true,
     [](const Sources& s) { return bytes_of(s.data->textures.texels()); }, kBuffer},
    {gpu::kSceneTexturedEmitters, "scene.textured_emitters", "scene_textured_emitters", nullptr,
     true, [](const Sources& s) { return bytes_of(s.data->textured_emitters); }, kBuffer},
    {gpu::kSceneVertexTangents, "scene.vertex_tangents", "scene_vertex_tangents", nullptr, true,
     [](const Sources& s) { return bytes_of(s.data->vertex_tangents); }, kBuffer},
    {gpu::kSceneVertexTexcoords1, "scene.vertex_texcoords1", "scene_vertex_texcoords1", nullptr,
     true, [](const Sources& s) { return bytes_of(s.data->vertex_texcoords1); }, kBuffer},
    // Rewritten when a volume moves (GpuScene::update_volumes).
    {gpu::kSceneVolumes, "scene.volumes", "scene_volumes", nullptr, false,
     [](const Sources& s) { return bytes_of(s.data->volumes); }, kBuffer},
    {gpu::kSceneVolumeCells, "scene.volume_cells", "scene_volume_cells", nullptr, true,
     [](const Sources& s) { return bytes_of(s.data->volume_cells); }, kBuffer},
    {gpu::kSceneVolumeValues, "scene.volume_values", "scene_volume_values", nullptr, true,
     [](const Sources& s) { return bytes_of(s.data->volume_values); }, kBuffer},
    // Rewritten with the light list when lights come or go (GpuScene::update_lights).
    {gpu::kSceneLightGrid, "scene.light_grid", "light_grid", nullptr, false,
     [](const Sources& s) { return bytes_of(s.data->light_grid.gpu_words()); }, kBuffer},
    {gpu::kSceneLightCells, "scene.light_cells", "light_cells", nullptr, false,
     [](const Sources& s) { return bytes_of(s.data->light_grid.light_cells()); }, kBuffer},
    {gpu::kSceneTlas, "scene.tlas", "scene_tlas", nullptr, false, nullptr,
     SceneResourceKind::AccelerationStructure},
}};
// clang-format on

namespace {
constexpr bool rows_in_slot_order() {
  for (std::uint32_t i = 0; i < kSceneBuffers.size(); ++i) {
    if (kSceneBuffers[i].slot != i) return false;
  }
  return true;
}
static_assert(rows_in_slot_order(), "kSceneBuffers: row i must describe slot i");
// "Exactly the acceleration-structure rows have no CPU bytes" is tested at run time
// (SceneBuffers.OnlyDeviceBuiltRowsHaveNoBytes): GCC's sanitizer builds do not fold the
// comparison of a lambda's function pointer with nullptr in a constant expression.
}  // namespace

void SceneHandles::declare_reads(runtime::graph::PassBuilder& builder,
                                 const runtime::Pipeline& pipeline) const {
  using runtime::graph::Access;
  for (const SceneBufferRow& row : kSceneBuffers) {
    const bool storage = pipeline.find_binding(row.shader_name) != nullptr;
    const bool texel =
        row.texel_name != nullptr && pipeline.find_binding(row.texel_name) != nullptr;
    if (!storage && !texel) continue;
    const runtime::graph::BufferHandle h = buffers[row.slot];
    if (!h.valid()) {
      throw RuntimeError(
          fmt::format("pipeline '{}' reads scene buffer '{}', which this frame's "
                      "SceneHandles do not hold",
                      pipeline.name(), row.graph_name));
    }
    if (row.kind == SceneResourceKind::AccelerationStructure) {
      builder.read(h, Access::AccelerationStructureRead);
      continue;
    }
    if (storage) builder.read(h, Access::StorageRead);
    if (texel) builder.read(h, Access::UniformTexelRead);
  }
}

void SceneHandles::bind(runtime::Bindings& bindings,
                        const runtime::graph::PassContext& ctx) const {
  for (const SceneBufferRow& row : kSceneBuffers) {
    if (row.kind == SceneResourceKind::AccelerationStructure) {
      if (bindings.has(row.shader_name)) bindings.acceleration_structure(row.shader_name, tlas);
      continue;
    }
    if (bindings.has(row.shader_name)) {
      bindings.buffer(row.shader_name, ctx.buffer(buffers[row.slot]), 0, VK_WHOLE_SIZE);
    }
    if (row.texel_name != nullptr && bindings.has(row.texel_name)) {
      bindings.texel_buffer(row.texel_name, texel_views[row.slot]);
    }
  }
}

}  // namespace lantern::lighting
