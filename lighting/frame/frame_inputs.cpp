// GBufferHandles read declarations and binding by name (frame_inputs.h).
#include "lighting/frame/frame_inputs.h"

#include <utility>

#include "runtime/gpu/bindings.h"
#include "runtime/gpu/pipeline.h"
#include "runtime/graph/pass_context.h"

namespace lantern::lighting {
namespace {

std::array<std::pair<const char*, runtime::graph::ImageHandle>, 6> named(const GBufferHandles& g) {
  return {{{"gbuffer_position", g.position},
           {"gbuffer_normal", g.normal},
           {"gbuffer_albedo_roughness", g.albedo_roughness},
           {"gbuffer_emission_metallic", g.emission_metallic},
           {"gbuffer_ids", g.ids},
           {"gbuffer_motion", g.motion}}};
}

}  // namespace

void GBufferHandles::declare_reads(runtime::graph::PassBuilder& builder,
                                   const runtime::Pipeline& pipeline) const {
  for (const auto& [name, h] : named(*this)) {
    if (pipeline.find_binding(name) != nullptr) {
      builder.read(h, runtime::graph::Access::StorageRead);
    }
  }
}

void GBufferHandles::bind(runtime::Bindings& bindings,
                          const runtime::graph::PassContext& ctx) const {
  for (const auto& [name, h] : named(*this)) {
    if (bindings.has(name)) bindings.image_view(name, ctx.view(h), VK_IMAGE_LAYOUT_GENERAL);
  }
}

}  // namespace lantern::lighting
