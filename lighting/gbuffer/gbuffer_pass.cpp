// gbuffer: raster G-buffer pass (see gbuffer_pass.h and shaders/gbuffer/gbuffer.{vert,frag}).
// Reads: scene frame constants, vertices, indices, materials, instances. Writes: gbuffer.position,
// .normal, .albedo_roughness, .emission_metallic, .ids, .motion, .depth (transient).
// History: none. Shape: gbuffer.draws (instance_count threads) then one indirect draw per
// instance inside one dynamic-rendering scope.
#include "lighting/gbuffer/gbuffer_pass.h"

#include <fmt/format.h>

#include <array>
#include <span>
#include <vector>

#include "engine/core/error.h"
#include "gbuffer/gbuffer_push.h"
#include "runtime/core/device.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/gpu/transfer.h"
#include "runtime/graph/graph_executor.h"
#include "shared/scene.h"

namespace lantern::lighting {
namespace {

using runtime::graph::Access;
using runtime::graph::BufferHandle;
using runtime::graph::ImageHandle;
using runtime::graph::PassBuilder;
using runtime::graph::PassContext;
using runtime::graph::PassKind;
using runtime::graph::RenderGraph;

// Attachment order = fragment output locations in shaders/gbuffer/gbuffer.frag.
constexpr std::array<VkFormat, 6> kColorFormats = {
    VK_FORMAT_R32G32B32A32_SFLOAT,  // position
    VK_FORMAT_R32G32B32A32_SFLOAT,  // normal
    VK_FORMAT_R16G16B16A16_SFLOAT,  // albedo_roughness
    VK_FORMAT_R32G32B32A32_SFLOAT,  // emission_metallic
    VK_FORMAT_R32G32B32A32_UINT,    // ids
    VK_FORMAT_R32G32B32A32_SFLOAT,  // motion
};
constexpr std::array<const char*, 6> kColorNames = {
    "gbuffer.position",          "gbuffer.normal", "gbuffer.albedo_roughness",
    "gbuffer.emission_metallic", "gbuffer.ids",    "gbuffer.motion"};
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr std::uint32_t kDrawCommandBytes = sizeof(VkDrawIndirectCommand);
static_assert(kDrawCommandBytes == 16, "gbuffer_draws.comp writes one uvec4 per draw");

// What a sky pixel holds: position.w = 0, ids.x = kNoInstance, everything else 0.
VkClearColorValue clear_value(std::size_t attachment) {
  VkClearColorValue value{};
  if (attachment == 4) {
    value.uint32[0] = gpu::kNoInstance;
    value.uint32[1] = gpu::kNoInstance;
    value.uint32[2] = gpu::kNoInstance;
    value.uint32[3] = 0;
  }
  return value;
}

struct DrawsData {
  BufferHandle instances;
  BufferHandle draws;
};

struct RasterData {
  BufferHandle frame_constants, vertices, indices, materials, instances, draws;
  std::array<ImageHandle, 6> colors;
  ImageHandle depth;
};

}  // namespace

GBufferPass::GBufferPass(runtime::Device& device, runtime::ShaderLibrary& shaders)
    : device_(device),
      draws_(device, shaders.load("gbuffer/gbuffer_draws.comp"),
             runtime::ComputePipelineDesc{.name = "gbuffer.draws", .constants = {}}),
      raster_(device, shaders.load("gbuffer/gbuffer.vert"), shaders.load("gbuffer/gbuffer.frag"),
              runtime::GraphicsPipelineDesc{
                  .name = "gbuffer",
                  .color_formats = {kColorFormats.begin(), kColorFormats.end()},
                  .depth_format = kDepthFormat,
                  .cull_mode = VK_CULL_MODE_NONE,
                  .depth_compare = VK_COMPARE_OP_LESS}) {}

GBufferHandles GBufferPass::add_pass(RenderGraph& graph, const SceneHandles& scene,
                                     const GpuScene& /*gpu_scene*/, std::uint32_t width,
                                     std::uint32_t height, std::uint32_t instance_count) {
  return add_pass(graph, scene, width, height, instance_count);
}

GBufferHandles GBufferPass::add_pass(RenderGraph& graph, const SceneHandles& scene,
                                     std::uint32_t width, std::uint32_t height,
                                     std::uint32_t instance_count) {
  if (width == 0 || height == 0) {
    throw InputError(fmt::format("gbuffer: render size {}x{} must be positive", width, height));
  }
  for (const auto& [handle, name] :
       {std::pair{scene.frame_constants, "frame_constants"}, std::pair{scene.vertices, "vertices"},
        std::pair{scene.indices, "indices"}, std::pair{scene.materials, "materials"},
        std::pair{scene.instances, "instances"}}) {
    if (!handle.valid()) {
      throw RuntimeError(fmt::format("gbuffer: scene handle '{}' is not set", name));
    }
  }

  BufferHandle draws;
  if (instance_count > 0) {
    const DrawsData& d = graph.add_pass<DrawsData>(
        "gbuffer.draws", PassKind::Compute,
        [&](PassBuilder& b, DrawsData& data) {
          data.instances = scene.instances;
          b.read(scene.instances, Access::StorageRead);
          data.draws = b.write(graph.create_buffer("gbuffer.draws", {std::uint64_t{instance_count} *
                                                                     kDrawCommandBytes}),
                               Access::StorageWrite);
        },
        [this, instance_count](PassContext& ctx, const DrawsData& data) {
          runtime::Bindings bindings(draws_);
          bindings.buffer("scene_instances", ctx.buffer(data.instances), 0, VK_WHOLE_SIZE)
              .buffer("gbuffer_draws", ctx.buffer(data.draws), 0, VK_WHOLE_SIZE);
          draws_.bind(ctx.cmd(), bindings);
          draws_.push_constants(ctx.cmd(), gpu::GBufferDrawsPush{instance_count});
          draws_.dispatch_threads(ctx.cmd(), instance_count);
        });
    draws = d.draws;
  }

  const RasterData& r = graph.add_pass<RasterData>(
      "gbuffer", PassKind::Graphics,
      [&](PassBuilder& b, RasterData& data) {
        data.frame_constants = scene.frame_constants;
        data.vertices = scene.vertices;
        data.indices = scene.indices;
        data.materials = scene.materials;
        data.instances = scene.instances;
        for (BufferHandle h : {scene.frame_constants, scene.vertices, scene.indices,
                               scene.materials, scene.instances}) {
          b.read(h, Access::StorageRead);
        }
        if (draws.valid()) {
          data.draws = draws;
          b.read(draws, Access::IndirectBuffer);
        }
        for (std::size_t i = 0; i < kColorFormats.size(); ++i) {
          data.colors[i] =
              b.write(graph.create_image(kColorNames[i], {{width, height, 1}, kColorFormats[i]}),
                      Access::ColorAttachment);
        }
        data.depth =
            b.write(graph.create_image("gbuffer.depth", {{width, height, 1}, kDepthFormat}),
                    Access::DepthAttachment);
      },
      [this, width, height, instance_count](PassContext& ctx, const RasterData& data) {
        const VkCommandBuffer cmd = ctx.cmd();
        std::array<runtime::ColorTarget, 6> targets{};
        for (std::size_t i = 0; i < targets.size(); ++i) {
          targets[i].view = ctx.view(data.colors[i]);
          targets[i].clear = clear_value(i);
        }
        const runtime::DepthTarget depth{.view = ctx.view(data.depth), .clear = 1.0f};
        runtime::begin_rendering(device_, cmd, VkExtent2D{width, height}, targets, &depth);
        if (instance_count > 0) {
          runtime::Bindings bindings(raster_);
          bindings.buffer("frame_constants", ctx.buffer(data.frame_constants), 0, VK_WHOLE_SIZE)
              .buffer("scene_vertices", ctx.buffer(data.vertices), 0, VK_WHOLE_SIZE)
              .buffer("scene_indices", ctx.buffer(data.indices), 0, VK_WHOLE_SIZE)
              .buffer("scene_materials", ctx.buffer(data.materials), 0, VK_WHOLE_SIZE)
              .buffer("scene_instances", ctx.buffer(data.instances), 0, VK_WHOLE_SIZE);
          raster_.bind(cmd, bindings);
          const VkBuffer draw_buffer = ctx.buffer(data.draws);
          for (std::uint32_t i = 0; i < instance_count; ++i) {
            raster_.push_constants(cmd, gpu::GBufferPush{i});
            vkCmdDrawIndirect(cmd, draw_buffer, VkDeviceSize{i} * kDrawCommandBytes, 1,
                              kDrawCommandBytes);
          }
        }
        runtime::end_rendering(device_, cmd);
      });

  GBufferHandles out;
  out.position = r.colors[0];
  out.normal = r.colors[1];
  out.albedo_roughness = r.colors[2];
  out.emission_metallic = r.colors[3];
  out.ids = r.colors[4];
  out.motion = r.colors[5];
  return out;
}

void GBufferPass::warm_up() {
  // One triangle covering a 1x1 target seen through an identity camera, uploaded to throw-away
  // buffers and run through the same passes as a real frame (so the fragment stage compiles too).
  gpu::FrameConstants constants{};
  constants.view_proj = glm::mat4(1.0f);
  constants.prev_view_proj = glm::mat4(1.0f);
  constants.inv_view_proj = glm::mat4(1.0f);
  constants.camera_position = glm::vec4(0.0f, 0.0f, -1.0f, 1.0f);
  constants.prev_camera_position = constants.camera_position;
  constants.frame = glm::uvec4(1, 1, 0, 1);
  std::array<gpu::GpuVertex, 3> vertices{};
  vertices[0].position_u = glm::vec4(-1.0f, -1.0f, 0.5f, 0.0f);
  vertices[1].position_u = glm::vec4(3.0f, -1.0f, 0.5f, 0.0f);
  vertices[2].position_u = glm::vec4(-1.0f, 3.0f, 0.5f, 0.0f);
  for (gpu::GpuVertex& v : vertices) v.normal_v = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
  const std::array<std::uint32_t, 3> indices = {0, 1, 2};
  const gpu::GpuMaterial material{};
  gpu::GpuInstance instance{};
  instance.object_to_world = glm::mat4(1.0f);
  instance.prev_object_to_world = glm::mat4(1.0f);
  instance.world_to_object = glm::mat4(1.0f);
  instance.geometry = glm::uvec4(0, 0, 3, 0);

  auto make = [&]<class T>(std::span<const T> values, const char* name) {
    runtime::Buffer buffer(device_, {.size = values.size_bytes(),
                                     .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                     .memory = runtime::MemoryUsage::DeviceLocal,
                                     .name = name});
    runtime::upload_buffer(device_, buffer, values);
    return buffer;
  };
  std::vector<runtime::Buffer> buffers;
  buffers.push_back(make(std::span<const gpu::FrameConstants>(&constants, 1), "warm_up.frame"));
  buffers.push_back(make(std::span<const gpu::GpuVertex>(vertices), "warm_up.vertices"));
  buffers.push_back(make(std::span<const std::uint32_t>(indices), "warm_up.indices"));
  buffers.push_back(make(std::span<const gpu::GpuMaterial>(&material, 1), "warm_up.materials"));
  buffers.push_back(make(std::span<const gpu::GpuInstance>(&instance, 1), "warm_up.instances"));

  RenderGraph graph;
  runtime::graph::GraphExecutor executor(device_);
  graph.begin_frame();
  runtime::graph::ImportInfo read_only;
  read_only.read_only = true;
  auto import = [&](std::size_t i) {
    return graph.import_buffer(buffers[i].name(), buffers[i].handle(), {buffers[i].size()},
                               read_only);
  };
  SceneHandles scene;
  scene.frame_constants = import(0);
  scene.vertices = import(1);
  scene.indices = import(2);
  scene.materials = import(3);
  scene.instances = import(4);
  const GBufferHandles out = add_pass(graph, scene, 1, 1, 1);
  // Keep the raster pass alive: a consumer of one of its images.
  struct Keep {};
  graph.add_pass<Keep>(
      "gbuffer.warm_up", PassKind::Compute,
      [&](PassBuilder& b, Keep&) {
        b.read(out.ids, Access::StorageRead);
        b.side_effect();
      },
      [](PassContext&, const Keep&) {});
  graph.bake(executor.compile_options());
  device_.submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
  graph.end_frame();
}

}  // namespace lantern::lighting
