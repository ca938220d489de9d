// Bindings: the resources for one pipeline's descriptors, set BY NAME as the shader spells them
// (`Bindings(pipeline).buffer("reservoirs", reservoirs).storage_image("radiance", hdr)`).
// Unknown names, wrong resource kinds and forgotten bindings are errors that name the shader's
// bindings, never silent mis-binds. A name the shader declares but never uses (left out of the
// layout by the reflection) is accepted and ignored; has() is true only for used ones.
#pragma once

#include <vulkan/vulkan.h>

#include <string_view>
#include <vector>

#include "runtime/gpu/spirv_reflect.h"

namespace lantern::runtime {

class Pipeline;
class Buffer;
class Image;

class Bindings {
 public:
  explicit Bindings(const Pipeline& pipeline);

  // Storage or uniform buffer (range VK_WHOLE_SIZE: to the end of the buffer).
  Bindings& buffer(std::string_view name, const Buffer& buffer, VkDeviceSize offset = 0,
                   VkDeviceSize range = VK_WHOLE_SIZE);
  Bindings& storage_image(std::string_view name, const Image& image,
                          VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL);
  // Sampled image or combined image sampler (the latter needs `sampler`).
  Bindings& sampled_image(std::string_view name, const Image& image,
                          VkSampler sampler = VK_NULL_HANDLE,
                          VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  Bindings& sampler(std::string_view name, VkSampler sampler);
  // Raw forms for resources not owned by runtime::Buffer/Image (e.g. swapchain views).
  Bindings& buffer(std::string_view name, VkBuffer buffer, VkDeviceSize offset, VkDeviceSize range);
  Bindings& image_view(std::string_view name, VkImageView view, VkImageLayout layout,
                       VkSampler sampler = VK_NULL_HANDLE);
  Bindings& acceleration_structure(std::string_view name, VkAccelerationStructureKHR structure);
  // Uniform or storage texel buffer (samplerBuffer / imageBuffer): a view (runtime/gpu/buffer_view.h).
  Bindings& texel_buffer(std::string_view name, VkBufferView view);
  // Whether the shader declares a binding of this name (for helpers that bind per variant).
  bool has(std::string_view name) const;

  const Pipeline& pipeline() const { return *pipeline_; }
  bool is_bound(std::string_view name) const;
  // Descriptor writes for vkCmdPushDescriptorSetKHR. Throws naming every unbound binding.
  // The returned writes point into this object: use them before it changes.
  std::vector<VkWriteDescriptorSet> writes() const;

 private:
  struct Slot {
    const DescriptorBinding* binding = nullptr;
    bool bound = false;
    VkDescriptorBufferInfo buffer{};
    VkDescriptorImageInfo image{};
    VkAccelerationStructureKHR structure = VK_NULL_HANDLE;
    VkBufferView texel_view = VK_NULL_HANDLE;
    VkWriteDescriptorSetAccelerationStructureKHR structure_write{
        VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
  };
  Slot& slot(std::string_view name, std::initializer_list<VkDescriptorType> accepted,
             const char* call);

  const Pipeline* pipeline_;
  mutable std::vector<Slot> slots_;
  Slot ignored_;  // target of bindings the shader declares but never uses
};

}  // namespace lantern::runtime
