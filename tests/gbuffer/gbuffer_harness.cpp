// GBufferHarness (gbuffer_harness.h).
#include "tests/gbuffer/gbuffer_harness.h"

#include <fmt/format.h>

#include <array>
#include <cstring>
#include <glm/gtc/packing.hpp>

#include "runtime/core/device.h"
#include "runtime/gpu/transfer.h"

namespace lantern::test {
namespace {

using runtime::graph::Access;
using runtime::graph::BufferHandle;
using runtime::graph::ImageHandle;
using runtime::graph::PassBuilder;
using runtime::graph::PassContext;
using runtime::graph::PassKind;

template <class T>
runtime::Buffer make_storage(runtime::Device& device, std::span<const T> values, const char* name) {
  std::vector<T> data(values.begin(), values.end());
  if (data.empty()) data.push_back(T{});
  runtime::Buffer buffer(device, {.size = data.size() * sizeof(T),
                                  .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  .memory = runtime::MemoryUsage::DeviceLocal,
                                  .name = name});
  runtime::upload_buffer(device, buffer, std::span<const T>(data));
  return buffer;
}

// Bytes per pixel of the six colour images, in GBufferHandles order.
constexpr std::array<std::uint32_t, 6> kPixelBytes = {16, 16, 8, 16, 16, 16};

}  // namespace

GBufferHarness::GBufferHarness(runtime::Device& device, runtime::ShaderLibrary& shaders,
                               const lighting::SceneData& scene,
                               const lighting::GBufferPassOptions& options)
    : device_(device),
      pass_(device, shaders,
            {.method = options.method, .textured = options.textured || !scene.textures.empty()}),
      instances_host_(scene.instances),
      frame_constants_(device, {.size = sizeof(gpu::FrameConstants),
                                .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                .memory = runtime::MemoryUsage::DeviceLocal,
                                .name = "test.frame_constants"}),
      vertices_(make_storage(device, std::span(scene.vertices), "test.vertices")),
      indices_(make_storage(device, std::span(scene.indices), "test.indices")),
      materials_(make_storage(device, std::span(scene.materials), "test.materials")),
      instances_(make_storage(device, std::span(scene.instances), "test.instances")),
      textures_(make_storage(device, std::span(scene.textures.records()), "test.textures")),
      texels_(make_storage(device, std::span(scene.textures.texels()), "test.texels")),
      vertex_tangents_(
          make_storage(device, std::span(scene.vertex_tangents), "test.vertex_tangents")),
      vertex_texcoords1_(
          make_storage(device, std::span(scene.vertex_texcoords1), "test.vertex_texcoords1")),
      executor_(device),
      timer_(device, 16) {
  if (options.method == lighting::GBufferMethod::Host) {
    std::vector<lighting::BvhInstanceDesc> descs(scene.instances.size());
    for (std::size_t i = 0; i < descs.size(); ++i) {
      descs[i].mesh = scene.bvh.instance_mesh(i);
      descs[i].object_to_world = scene.instances[i].object_to_world;
      descs[i].user_id = static_cast<std::uint32_t>(i);
      descs[i].fixed = scene.bvh.merged(i);
    }
    host_ = std::make_unique<lighting::HostVisibility>(device, scene.bvh, descs);
  }
}

void GBufferHarness::set_instances(std::span<const gpu::GpuInstance> instances) {
  instances_ = make_storage(device_, instances, "test.instances");
  instances_host_.assign(instances.begin(), instances.end());
}

std::optional<GBufferImages> GBufferHarness::render(const gpu::FrameConstants& constants,
                                                    bool read_back) {
  const std::uint32_t width = constants.frame.x;
  const std::uint32_t height = constants.frame.y;
  runtime::upload_buffer(device_, frame_constants_,
                         std::span<const gpu::FrameConstants>(&constants, 1));
  if (read_back && (readback_width_ != width || readback_height_ != height)) {
    readback_.clear();
    for (std::uint32_t bytes : kPixelBytes) {
      readback_.emplace_back(device_,
                             runtime::BufferDesc{.size = std::size_t{width} * height * bytes,
                                                 .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                 .memory = runtime::MemoryUsage::Readback,
                                                 .name = "test.gbuffer_readback"});
    }
    readback_width_ = width;
    readback_height_ = height;
  }

  graph_.begin_frame();
  runtime::graph::ImportInfo read_only;
  read_only.read_only = true;
  auto import = [&](const runtime::Buffer& b) {
    return graph_.import_buffer(b.name(), b.handle(), {b.size()}, read_only);
  };
  lighting::SceneHandles scene;
  scene[gpu::kSceneFrameConstants] = import(frame_constants_);
  scene[gpu::kSceneVertices] = import(vertices_);
  scene[gpu::kSceneIndices] = import(indices_);
  scene[gpu::kSceneMaterials] = import(materials_);
  scene[gpu::kSceneInstances] = import(instances_);
  scene[gpu::kSceneTextures] = import(textures_);
  scene[gpu::kSceneTexels] = import(texels_);
  scene[gpu::kSceneVertexTangents] = import(vertex_tangents_);
  scene[gpu::kSceneVertexTexcoords1] = import(vertex_texcoords1_);
  const lighting::GBufferHandles g =
      host_ ? pass_.add_host_pass(graph_, scene, width, height, *host_, constants)
            : pass_.add_pass(graph_, scene, width, height,
                             std::span<const gpu::GpuInstance>(instances_host_));
  const std::array<ImageHandle, 6> images = {g.position,          g.normal, g.albedo_roughness,
                                             g.emission_metallic, g.ids,    g.motion};

  struct Copy {
    std::array<ImageHandle, 6> images;
    std::array<BufferHandle, 6> buffers;
  };
  graph_.add_pass<Copy>(
      "test.gbuffer_readback", PassKind::Transfer,
      [&](PassBuilder& b, Copy& d) {
        runtime::graph::ImportInfo host_read;
        host_read.final = runtime::graph::AccessState{
            VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
        for (std::size_t i = 0; i < images.size(); ++i) {
          d.images[i] = images[i];
          if (read_back) {
            b.read(images[i], Access::TransferSrc);
            d.buffers[i] = b.write(
                graph_.import_buffer(fmt::format("test.readback{}", i), readback_[i].handle(),
                                     {readback_[i].size()}, host_read),
                Access::TransferDst);
          }
        }
        if (!read_back) b.read(images[4], Access::TransferSrc);  // keeps gbuffer alive
        b.side_effect();
      },
      [read_back, width, height](PassContext& ctx, const Copy& d) {
        if (!read_back) return;
        for (std::size_t i = 0; i < d.images.size(); ++i) {
          VkBufferImageCopy region{};
          region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
          region.imageExtent = {width, height, 1};
          vkCmdCopyImageToBuffer(ctx.cmd(), ctx.image(d.images[i]),
                                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, ctx.buffer(d.buffers[i]), 1,
                                 &region);
        }
      });

  graph_.bake(executor_.compile_options());
  device_.submit_and_wait([&](VkCommandBuffer cmd) {
    timer_.reset(cmd);
    executor_.record(graph_, cmd, &timer_);
  });
  graph_.end_frame();
  timings_ = timer_.resolve();
  if (!read_back) return std::nullopt;

  GBufferImages out;
  out.width = width;
  out.height = height;
  const std::size_t n = std::size_t{width} * height;
  auto floats = [&](std::size_t i, std::vector<glm::vec4>& dst) {
    dst.resize(n);
    std::memcpy(dst.data(), readback_[i].mapped(), n * sizeof(glm::vec4));
  };
  floats(0, out.position);
  floats(1, out.normal);
  floats(3, out.emission_metallic);
  floats(5, out.motion);
  out.ids.resize(n);
  std::memcpy(out.ids.data(), readback_[4].mapped(), n * sizeof(glm::uvec4));
  out.albedo_roughness.resize(n);
  std::vector<std::uint16_t> half(n * 4);
  std::memcpy(half.data(), readback_[2].mapped(), half.size() * sizeof(std::uint16_t));
  for (std::size_t p = 0; p < n; ++p) {
    for (int c = 0; c < 4; ++c) out.albedo_roughness[p][c] = glm::unpackHalf1x16(half[p * 4 + c]);
  }
  return out;
}

double GBufferHarness::last_ms(const std::string& name) const {
  for (const auto& t : timings_) {
    if (t.name == name) return t.ms;
  }
  return -1.0;
}

}  // namespace lantern::test
