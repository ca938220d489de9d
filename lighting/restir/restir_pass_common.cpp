// Dispatch shape and name-based binding helpers of the restir.* passes.
#include "lighting/restir/restir_pass_common.h"

#include "lighting/frame/tile_order.h"
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

}  // namespace lantern::lighting::restir_detail
