// Descriptions of graph resources (what to create) and of how a pass uses one (Access), plus the
// synchronisation state a use implies (stages, access mask, image layout).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

namespace lantern::runtime::graph {

struct BufferDesc {
  VkDeviceSize size = 0;
  friend bool operator==(const BufferDesc&, const BufferDesc&) = default;
};

struct ImageDesc {
  VkExtent3D extent{1, 1, 1};
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t mip_levels = 1;
  uint32_t array_layers = 1;
  friend bool operator==(const ImageDesc& a, const ImageDesc& b) {
    return a.extent.width == b.extent.width && a.extent.height == b.extent.height &&
           a.extent.depth == b.extent.depth && a.format == b.format &&
           a.mip_levels == b.mip_levels && a.array_layers == b.array_layers;
  }
};

// The format of a graph-made buffer's texel view (UniformTexelRead): one uvec4 per 16 bytes,
// which a shader reinterprets (uintBitsToFloat) as the record it reads.
inline constexpr VkFormat kGraphTexelFormat = VK_FORMAT_R32G32B32A32_UINT;
inline constexpr VkDeviceSize kGraphTexelBytes = 16;

// How a pass uses a resource. Reads keep the version; writes produce a new one.
enum class Access : uint8_t {
  StorageRead,       // buffer or image, read in shaders
  StorageWrite,      // buffer or image, written in shaders (previous contents discarded)
  StorageReadWrite,  // buffer or image, read-modify-write in shaders (needs written contents)
  UniformRead,       // buffer
  UniformTexelRead,  // buffer, through a uniform texel buffer view (texelFetch on a
                     // [u]samplerBuffer / [u]textureBuffer): SHADER_SAMPLED_READ; a graph-made
                     // buffer's view is kGraphTexelFormat (PassContext::texel_view)
  Sampled,           // image through a sampler
  ColorAttachment,   // image, written by rasterisation
  DepthAttachment,   // image, depth test and write
  DepthRead,         // image, depth test only
  TransferSrc,       // buffer or image, copy source
  TransferDst,       // buffer or image, copy destination
  VertexBuffer,      // buffer
  IndexBuffer,       // buffer
  IndirectBuffer,    // buffer, indirect dispatch/draw arguments
  // VK_KHR_acceleration_structure (buffers backing a structure, its build inputs and scratch):
  AccelerationStructureBuildInput,  // buffer read by a build (instance records, vertices)
  AccelerationStructureBuild,       // buffer written by a build: the structure's storage or the
                                    // scratch (previous contents discarded)
  AccelerationStructureRead,        // buffer of a structure traced in shaders (ray query)
  // A Host pass's use of a host-visible (mapped) buffer: read and updated in place on the CPU.
  HostReadWrite,
};

// Where a pass runs; decides the shader stages its shader accesses happen in.
// Host: work the CPU does between two submissions (e.g. visibility answered by Embree on a CPU
// device): the executor submits the passes before it and waits, runs it, then records the rest.
enum class PassKind : uint8_t { Compute, Graphics, Transfer, Host };

[[nodiscard]] bool is_write(Access access);
[[nodiscard]] bool is_read(Access access);  // StorageReadWrite is both
[[nodiscard]] bool allowed_on_buffer(Access access);
[[nodiscard]] bool allowed_on_image(Access access);
[[nodiscard]] const char* access_name(Access access);
[[nodiscard]] const char* pass_kind_name(PassKind kind);

// The synchronisation scope of one use (or the last known state of a resource).
struct AccessState {
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // images only
  friend bool operator==(const AccessState&, const AccessState&) = default;
};

// State implied by using a resource with `access` in a pass of `kind`.
[[nodiscard]] AccessState access_state(Access access, PassKind kind, bool is_image);

// Usage flags a transient must be created with to allow `access`.
[[nodiscard]] VkBufferUsageFlags buffer_usage(Access access);
[[nodiscard]] VkImageUsageFlags image_usage(Access access);

// Short text forms for dumps, e.g. "COMPUTE_SHADER", "SHADER_STORAGE_WRITE", "GENERAL".
[[nodiscard]] std::string stage_names(VkPipelineStageFlags2 stages);
[[nodiscard]] std::string access_names(VkAccessFlags2 access);
[[nodiscard]] const char* layout_name(VkImageLayout layout);

}  // namespace lantern::runtime::graph
