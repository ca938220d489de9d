// Pipeline warm-up: bind each pipeline with small dummy resources and dispatch zero workgroups.
// lavapipe JIT-compiles the shader when a dispatch is recorded-and-executed, even an empty one,
// so the compile cost moves out of the first timed frame without running the shader on junk data.
#include <fmt/format.h>

#include <algorithm>
#include <deque>
#include <memory>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"
#include "runtime/gpu/acceleration_structure.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/buffer_view.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/image.h"
#include "runtime/gpu/transfer.h"

namespace lantern::runtime {

void warm_up(Device& device, std::span<const ComputePipeline* const> pipelines) {
  std::vector<Buffer> buffers;
  std::vector<Image> images;
  std::deque<BufferView> views;  // stable addresses; destroyed before `buffers`
  std::vector<Bindings> bindings;
  buffers.reserve(64);
  images.reserve(64);
  VkSampler sampler = VK_NULL_HANDLE;
  VkSamplerCreateInfo sampler_info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  // Ray-query shaders get one empty TLAS (built in the warm-up submit before the dispatches).
  struct EmptyTlas {
    Buffer instances;
    AccelerationStructureBuild build;
    AccelerationStructure tlas;
    std::unique_ptr<ScratchBuffer> scratch;
  };
  std::unique_ptr<EmptyTlas> empty_tlas;
  auto get_empty_tlas = [&]() -> VkAccelerationStructureKHR {
    if (empty_tlas) return empty_tlas->tlas.handle();
    empty_tlas = std::make_unique<EmptyTlas>();
    EmptyTlas& e = *empty_tlas;
    e.instances = Buffer(
        device,
        BufferDesc{.size = sizeof(VkAccelerationStructureInstanceKHR),
                   .usage = VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                            VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR,
                   .name = "warm_up.tlas_instances"});
    e.build = instance_tlas_build(e.instances.device_address(), 0);
    const auto sizes = acceleration_structure_build_sizes(device, e.build);
    e.tlas = AccelerationStructure(device, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
                                   sizes.accelerationStructureSize, "warm_up.tlas");
    e.scratch = std::make_unique<ScratchBuffer>(device, "warm_up.tlas_scratch");
    e.scratch->reserve(std::max<VkDeviceSize>(sizes.buildScratchSize, 256));
    return e.tlas.handle();
  };

  for (const ComputePipeline* p : pipelines) {
    Bindings& b = bindings.emplace_back(*p);
    for (const auto& binding : p->bindings()) {
      switch (binding.type) {
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
          b.buffer(
              binding.name,
              buffers.emplace_back(device, BufferDesc{.size = 4096,
                                                      .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                               VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                                      .name = "warm_up." + binding.name}));
          break;
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
        case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: {
          const bool storage = binding.type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
          const VkFormat format = binding.image_format != VK_FORMAT_UNDEFINED
                                      ? binding.image_format
                                      : VK_FORMAT_R32G32B32A32_SFLOAT;
          Image& image = images.emplace_back(
              device,
              ImageDesc{.width = 1,
                        .height = 1,
                        .format = format,
                        .usage = static_cast<VkImageUsageFlags>(
                            storage ? VK_IMAGE_USAGE_STORAGE_BIT : VK_IMAGE_USAGE_SAMPLED_BIT),
                        .name = "warm_up." + binding.name});
          if (storage) {
            b.storage_image(binding.name, image, VK_IMAGE_LAYOUT_GENERAL);
          } else {
            if (sampler == VK_NULL_HANDLE)
              VK_CHECK(vkCreateSampler(device.handle(), &sampler_info, nullptr, &sampler));
            b.sampled_image(binding.name, image, sampler, VK_IMAGE_LAYOUT_GENERAL);
          }
          break;
        }
        case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
        case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER: {
          // rgba32ui unless the shader declares a format: the project's texel buffers are
          // utextureBuffer views of uvec4 arrays (lib/bvh_traverse.glsl).
          const bool storage = binding.type == VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
          const VkFormat format = binding.image_format != VK_FORMAT_UNDEFINED
                                      ? binding.image_format
                                      : VK_FORMAT_R32G32B32A32_UINT;
          const Buffer& buffer = buffers.emplace_back(
              device, BufferDesc{.size = 4096,
                                 .usage = static_cast<VkBufferUsageFlags>(
                                     storage ? VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT
                                             : VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT),
                                 .name = "warm_up." + binding.name});
          b.texel_buffer(binding.name,
                         views.emplace_back(device, buffer, format, "warm_up." + binding.name)
                             .handle());
          break;
        }
        case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR:
          b.acceleration_structure(binding.name, get_empty_tlas());
          break;
        default:
          throw RuntimeError(
              fmt::format("warm_up: pipeline '{}' binding '{}' ({}) has no dummy resource",
                          p->name(), binding.name, descriptor_type_name(binding.type)));
      }
    }
  }

  std::vector<std::byte> zeros(device.caps().max_push_constant_bytes);
  device.submit_and_wait([&](VkCommandBuffer cmd) {
    if (empty_tlas) {
      empty_tlas->tlas.record_build(cmd, empty_tlas->build, empty_tlas->scratch->address());
      record_acceleration_structure_barrier(device, cmd);
    }
    for (const Image& image : images)
      transition_image(device, cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    for (std::size_t i = 0; i < pipelines.size(); ++i) {
      const ComputePipeline& p = *pipelines[i];
      p.bind(cmd, bindings[i]);
      if (p.push_constant_bytes() > 0) p.push_constants(cmd, zeros.data(), p.push_constant_bytes());
      p.dispatch(cmd, 0, 0, 0);
    }
  });
  if (sampler != VK_NULL_HANDLE) vkDestroySampler(device.handle(), sampler, nullptr);
}

}  // namespace lantern::runtime
