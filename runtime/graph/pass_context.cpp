// PassContext: handle → Vulkan object resolution, checked against the pass's declarations.
#include "runtime/graph/pass_context.h"

#include <fmt/format.h>

#include <algorithm>

#include "runtime/graph/graph_compiler.h"

namespace lantern::runtime::graph {

const PhysicalResource& PassContext::resolve(uint32_t resource, bool image) const {
  const PassDecl& pass = decl_.passes[pass_];
  const bool declared = std::any_of(pass.uses.begin(), pass.uses.end(),
                                    [&](const ResourceUse& u) { return u.resource == resource; });
  if (resource >= decl_.resources.size() || !declared)
    throw RenderGraphError(fmt::format(
        "pass '{}' resolves resource #{} it did not declare in its setup", pass.name, resource));
  if (decl_.resources[resource].is_image != image)
    throw RenderGraphError(fmt::format("pass '{}' resolves '{}' as the wrong kind", pass.name,
                                       decl_.resources[resource].name));
  return physical_[resource];
}

VkBufferView PassContext::texel_view(BufferHandle h) const {
  const PhysicalResource& p = resolve(h.index, false);
  const PassDecl& pass = decl_.passes[pass_];
  const bool texel_read = std::any_of(pass.uses.begin(), pass.uses.end(), [&](const ResourceUse& u) {
    return u.resource == h.index && u.access == Access::UniformTexelRead;
  });
  const ResourceDecl& r = decl_.resources[h.index];
  if (!texel_read)
    throw RenderGraphError(fmt::format(
        "pass '{}' asks for a texel view of '{}', which it did not declare as a texel read",
        pass.name, r.name));
  if (p.texel_view == VK_NULL_HANDLE)
    throw RenderGraphError(fmt::format(
        "pass '{}' reads '{}' as texels, but it has no texel view: {}", pass.name, r.name,
        r.origin == Origin::Imported
            ? "an imported buffer brings none"
            : fmt::format("{} B is no whole texel or more texels than the device's "
                          "maxTexelBufferElements",
                          r.buffer.size)));
  return p.texel_view;
}

const ImageDesc& PassContext::image_desc(ImageHandle h) const {
  resolve(h.index, true);
  return decl_.resources[h.index].image;
}

}  // namespace lantern::runtime::graph
