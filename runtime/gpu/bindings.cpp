// Name-checked descriptor bindings turned into push-descriptor writes.
#include "runtime/gpu/bindings.h"

#include <fmt/format.h>

#include <algorithm>

#include "engine/core/error.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/image.h"
#include "runtime/gpu/pipeline.h"

namespace lantern::runtime {

Bindings::Bindings(const Pipeline& pipeline) : pipeline_(&pipeline) {
  for (const auto& b : pipeline.bindings()) slots_.push_back(Slot{.binding = &b});
}

Bindings::Slot& Bindings::slot(std::string_view name,
                               std::initializer_list<VkDescriptorType> accepted, const char* call) {
  auto it = std::find_if(slots_.begin(), slots_.end(),
                         [&](const Slot& s) { return s.binding->name == name; });
  if (it == slots_.end() && pipeline_->declares_unused(name)) {
    ignored_ = Slot{};  // declared, never read by the shader: not in the layout, nothing to write
    return ignored_;
  }
  if (it == slots_.end()) {
    std::string known;
    for (const auto& s : slots_)
      known += fmt::format("{}{} ({})", known.empty() ? "" : ", ", s.binding->name,
                           descriptor_type_name(s.binding->type));
    throw RuntimeError(fmt::format("pipeline '{}': no binding named '{}' (shader bindings: {})",
                                   pipeline_->name(), name, known.empty() ? "none" : known));
  }
  if (std::find(accepted.begin(), accepted.end(), it->binding->type) == accepted.end())
    throw RuntimeError(
        fmt::format("pipeline '{}': binding '{}' is a {}; Bindings::{} cannot bind it",
                    pipeline_->name(), name, descriptor_type_name(it->binding->type), call));
  it->bound = true;
  return *it;
}

Bindings& Bindings::buffer(std::string_view name, VkBuffer buffer, VkDeviceSize offset,
                           VkDeviceSize range) {
  slot(name, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}, "buffer")
      .buffer = {buffer, offset, range};
  return *this;
}

Bindings& Bindings::buffer(std::string_view name, const Buffer& buffer, VkDeviceSize offset,
                           VkDeviceSize range) {
  return this->buffer(name, buffer.handle(), offset, range);
}

Bindings& Bindings::storage_image(std::string_view name, const Image& image, VkImageLayout layout) {
  slot(name, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}, "storage_image").image = {VK_NULL_HANDLE,
                                                                           image.view(), layout};
  return *this;
}

Bindings& Bindings::sampled_image(std::string_view name, const Image& image, VkSampler sampler,
                                  VkImageLayout layout) {
  Slot& s =
      slot(name, {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
           "sampled_image");
  if (s.binding->type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER && sampler == VK_NULL_HANDLE)
    throw RuntimeError(
        fmt::format("pipeline '{}': binding '{}' is a combined image sampler: pass a sampler",
                    pipeline_->name(), name));
  s.image = {sampler, image.view(), layout};
  return *this;
}

Bindings& Bindings::sampler(std::string_view name, VkSampler sampler) {
  slot(name, {VK_DESCRIPTOR_TYPE_SAMPLER}, "sampler").image = {sampler, VK_NULL_HANDLE,
                                                               VK_IMAGE_LAYOUT_UNDEFINED};
  return *this;
}

Bindings& Bindings::image_view(std::string_view name, VkImageView view, VkImageLayout layout,
                               VkSampler sampler) {
  slot(name,
       {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE,
        VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
       "image_view")
      .image = {sampler, view, layout};
  return *this;
}

Bindings& Bindings::acceleration_structure(std::string_view name,
                                           VkAccelerationStructureKHR structure) {
  slot(name, {VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR}, "acceleration_structure").structure =
      structure;
  return *this;
}

Bindings& Bindings::texel_buffer(std::string_view name, VkBufferView view) {
  slot(name, {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER},
       "texel_buffer")
      .texel_view = view;
  return *this;
}

bool Bindings::has(std::string_view name) const {
  return std::any_of(slots_.begin(), slots_.end(),
                     [&](const Slot& s) { return s.binding->name == name; });
}

bool Bindings::is_bound(std::string_view name) const {
  return std::any_of(slots_.begin(), slots_.end(),
                     [&](const Slot& s) { return s.bound && s.binding->name == name; });
}

std::vector<VkWriteDescriptorSet> Bindings::writes() const {
  std::string unbound;
  for (const auto& s : slots_)
    if (!s.bound) unbound += fmt::format("{}'{}'", unbound.empty() ? "" : ", ", s.binding->name);
  if (!unbound.empty())
    throw RuntimeError(
        fmt::format("pipeline '{}': bindings not set: {}", pipeline_->name(), unbound));

  std::vector<VkWriteDescriptorSet> writes;
  writes.reserve(slots_.size());
  for (auto& s : slots_) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = s.binding->binding;
    w.descriptorCount = 1;
    w.descriptorType = s.binding->type;
    switch (s.binding->type) {
      case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
      case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
        w.pBufferInfo = &s.buffer;
        break;
      case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR:
        s.structure_write.accelerationStructureCount = 1;
        s.structure_write.pAccelerationStructures = &s.structure;
        w.pNext = &s.structure_write;
        break;
      case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
      case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER:
        w.pTexelBufferView = &s.texel_view;
        break;
      default:
        w.pImageInfo = &s.image;
        break;
    }
    writes.push_back(w);
  }
  return writes;
}

}  // namespace lantern::runtime
