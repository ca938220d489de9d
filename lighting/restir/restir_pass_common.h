// What the restir.* pass files share: the shuffled 8x8 tile dispatch shape
// (lighting/frame/tile_order.h), and binding graph
// resources by the names the shaders give them (scene buffers, G-buffer images, the BVH behind
// shaders/lib/visibility.glsl's compute backend).
#pragma once

#include <cstdint>
#include <string_view>

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/bindings.h"
#include "runtime/graph/pass_context.h"

namespace lantern::lighting::restir_detail {

// Number of 8x8 tiles (= workgroups) covering width x height (lighting/frame/tile_order.h).
std::uint32_t tile_count(std::uint32_t width, std::uint32_t height);

// Binds graph buffer `h` as the storage buffer named `name`.
void bind_buffer(runtime::Bindings& b, const runtime::graph::PassContext& ctx,
                 std::string_view name, runtime::graph::BufferHandle h);
// Binds graph image `h` as the storage image named `name` (layout GENERAL).
void bind_image(runtime::Bindings& b, const runtime::graph::PassContext& ctx,
                std::string_view name, runtime::graph::ImageHandle h);
// Binds what lib/visibility.glsl's compute backend declares: the BVH header (storage) and the
// nodes, triangles and instances as rgba32ui texel views (the default; GpuScene owns the views)
// or as storage buffers (VIS_BVH_STORAGE_BUFFERS). The pass declares reads of the BVH buffers as
// SceneHandles::declare_reads does (StorageRead and UniformTexelRead).
void bind_visibility(runtime::Bindings& b, const runtime::graph::PassContext& ctx,
                     const SceneHandles& handles, const GpuScene* scene);

// Every restir.* shader sees the environment map (restir_common.glsl includes
// lib/environment.glsl): declares reads of env_header/texels/marginal/conditional, and binds them.
void declare_environment_reads(runtime::graph::PassBuilder& b, const SceneHandles& handles);
void bind_environment(runtime::Bindings& b, const runtime::graph::PassContext& ctx,
                      const SceneHandles& handles);

}  // namespace lantern::lighting::restir_detail
