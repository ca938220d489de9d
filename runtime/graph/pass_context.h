// What a pass's execute callback receives: the command buffer and the real Vulkan objects behind
// the handles it declared (resolving an undeclared handle is an error, not a silent hazard).
#pragma once

#include <vulkan/vulkan.h>

#include <span>
#include <string>

#include "runtime/graph/graph_decl.h"

namespace lantern::runtime::graph {

struct PhysicalResource {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkBufferView texel_view = VK_NULL_HANDLE;  // kGraphTexelFormat, where some pass reads texels
};

class PassContext {
 public:
  PassContext(VkCommandBuffer cmd, const GraphDecl& decl, uint32_t pass,
              std::span<const PhysicalResource> physical)
      : cmd_(cmd), decl_(decl), pass_(pass), physical_(physical) {}

  [[nodiscard]] VkCommandBuffer cmd() const { return cmd_; }
  [[nodiscard]] const std::string& pass_name() const { return decl_.passes[pass_].name; }

  [[nodiscard]] VkBuffer buffer(BufferHandle h) const { return resolve(h.index, false).buffer; }
  [[nodiscard]] VkDeviceSize buffer_size(BufferHandle h) const {
    return resolve(h.index, false).size;
  }
  // The buffer's texel view (kGraphTexelFormat over the whole buffer), for a buffer this pass
  // declared with Access::UniformTexelRead.
  [[nodiscard]] VkBufferView texel_view(BufferHandle h) const;
  [[nodiscard]] VkImage image(ImageHandle h) const { return resolve(h.index, true).image; }
  [[nodiscard]] VkImageView view(ImageHandle h) const { return resolve(h.index, true).view; }
  [[nodiscard]] const ImageDesc& image_desc(ImageHandle h) const;

 private:
  const PhysicalResource& resolve(uint32_t resource, bool image) const;

  VkCommandBuffer cmd_;
  const GraphDecl& decl_;
  uint32_t pass_;
  std::span<const PhysicalResource> physical_;
};

}  // namespace lantern::runtime::graph
