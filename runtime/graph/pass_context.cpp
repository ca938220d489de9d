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

const ImageDesc& PassContext::image_desc(ImageHandle h) const {
  resolve(h.index, true);
  return decl_.resources[h.index].image;
}

}  // namespace lantern::runtime::graph
