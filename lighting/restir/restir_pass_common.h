// What the restir.* pass files share: the shuffled 8x8 tile dispatch shape
// (lighting/frame/tile_order.h) and binding a pass's own graph resources by the names the shaders
// give them (the scene and the G-buffer bind themselves: SceneHandles, GBufferHandles).
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
}  // namespace lantern::lighting::restir_detail
