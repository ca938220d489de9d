// gbuffer: the G-buffer of shaders/shared/gbuffer.h (see gbuffer_pass.h for the passes).
// Reads: scene frame constants, vertices, indices, materials, instances. Writes: gbuffer.position,
// .normal, .albedo_roughness, .emission_metallic, .ids, .motion (returned), plus internal
// transients (gbuffer.chunks, .dispatch, .draw, .triangles, .clip, .visibility, .depth).
// History: none. Shape (visibility method): gbuffer.draws (one workgroup) -> gbuffer.cull
// (indirect, one workgroup per 128 triangles of an instance) -> gbuffer (one indirect draw of the
// kept triangles) -> gbuffer.resolve (one full-screen triangle). Forward method: gbuffer.draws ->
// gbuffer (one indirect draw per instance). Host method: gbuffer.host (a host pass: Embree writes
// gbuffer.host_hits) -> gbuffer.resolve ("hosthits" variant). Auto picks per frame
// (GBufferPass::method_for).
#include "lighting/gbuffer/gbuffer_pass.h"

#include "shared/textures.h"

#include <fmt/format.h>

#include <array>
#include <span>
#include <vector>

#include "engine/core/error.h"
#include "gbuffer/gbuffer_push.h"
#include "lighting/scene/gpu_scene.h"
#include "lighting/visibility/host_visibility.h"
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

// Attachment order = fragment output locations in gbuffer.frag and gbuffer_resolve.frag.
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
constexpr std::size_t kIdsAttachment = 4;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
// gbuffer.visibility: the gbuffer.cull list entry of the closest triangle; kNoInstance = sky.
constexpr VkFormat kVisibilityFormat = VK_FORMAT_R32_UINT;
constexpr std::uint32_t kDrawCommandBytes = sizeof(VkDrawIndirectCommand);
static_assert(kDrawCommandBytes == 16, "gbuffer_draws.comp writes one uvec4 per draw");
constexpr std::uint64_t kDispatchBytes = 16;       // VkDispatchIndirectCommand + padding
constexpr std::uint64_t kTriangleRecordBytes = 8;  // uvec2 (instance, triangle)
constexpr std::uint64_t kTriangleClipBytes = 48;   // three vec4 clip positions

// What a sky pixel holds: position.w = 0, ids.x = kNoInstance, everything else 0.
VkClearColorValue clear_value(std::size_t attachment) {
  VkClearColorValue value{};
  if (attachment == kIdsAttachment) {
    value.uint32[0] = gpu::kNoInstance;
    value.uint32[1] = gpu::kNoInstance;
    value.uint32[2] = gpu::kNoInstance;
    value.uint32[3] = 0;
  }
  return value;
}

VkClearColorValue visibility_clear() {
  VkClearColorValue value{};
  value.uint32[0] = gpu::kNoInstance;
  return value;
}

struct DrawsData {
  SceneHandles scene;
  BufferHandle chunks, dispatch, draw;
};

struct CullData {
  SceneHandles scene;
  BufferHandle chunks, dispatch, draw, triangles, clip;
};

struct VisibilityData {
  SceneHandles scene;
  BufferHandle draw, clip, triangles;
  ImageHandle visibility, depth;
};

struct ResolveData {
  SceneHandles scene;
  BufferHandle triangles;
  ImageHandle visibility;
  std::array<ImageHandle, 6> colors;
};

struct ForwardData {
  SceneHandles scene;
  BufferHandle draws;
  std::array<ImageHandle, 6> colors;
  ImageHandle depth;
};

// `textured`: the kTextured specialisation constant of the fragment stage.
runtime::GraphicsPipelineDesc raster_desc(const char* name, std::vector<VkFormat> colors,
                                          bool depth, bool textured) {
  return runtime::GraphicsPipelineDesc{.name = name,
                                       .color_formats = std::move(colors),
                                       .depth_format = depth ? kDepthFormat : VK_FORMAT_UNDEFINED,
                                       .cull_mode = VK_CULL_MODE_NONE,
                                       .depth_test = depth,
                                       .depth_write = depth,
                                       .depth_compare = VK_COMPARE_OP_LESS,
                                       .constants = runtime::SpecConstants().set("kTextured",
                                                                                 textured)};
}

GBufferHandles handles(const std::array<ImageHandle, 6>& colors) {
  GBufferHandles out;
  out.position = colors[0];
  out.normal = colors[1];
  out.albedo_roughness = colors[2];
  out.emission_metallic = colors[3];
  out.ids = colors[4];
  out.motion = colors[5];
  return out;
}

}  // namespace

GBufferPass::GBufferPass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                         const GBufferPassOptions& options)
    : device_(device), options_(options) {
  const std::vector<VkFormat> colors(kColorFormats.begin(), kColorFormats.end());
  if (options_.method == GBufferMethod::Auto || options_.method == GBufferMethod::Forward) {
    forward_draws_.emplace(
        device, shaders.load("gbuffer/gbuffer_draws.comp"),
        runtime::ComputePipelineDesc{.name = "gbuffer.draws",
                                     .constants = runtime::SpecConstants().set("kForward", true)});
    forward_raster_.emplace(device, shaders.load("gbuffer/gbuffer.vert"),
                            shaders.load("gbuffer/gbuffer.frag"),
                            raster_desc("gbuffer", colors, true, options_.textured));
  }
  if (options_.method == GBufferMethod::Auto || options_.method == GBufferMethod::Visibility) {
    draws_.emplace(
        device, shaders.load("gbuffer/gbuffer_draws.comp"),
        runtime::ComputePipelineDesc{.name = "gbuffer.draws",
                                     .constants = runtime::SpecConstants().set("kForward", false)});
    cull_.emplace(device, shaders.load("gbuffer/gbuffer_cull.comp"),
                  runtime::ComputePipelineDesc{.name = "gbuffer.cull", .constants = {}});
    raster_.emplace(device, shaders.load("gbuffer/gbuffer_visibility.vert"),
                    shaders.load("gbuffer/gbuffer_visibility.frag"),
                    raster_desc("gbuffer", {kVisibilityFormat}, true, options_.textured));
    resolve_.emplace(device, shaders.load("gbuffer/gbuffer_resolve.vert"),
                     shaders.load("gbuffer/gbuffer_resolve.frag"),
                     raster_desc("gbuffer.resolve", colors, false, options_.textured));
  }
  if (options_.method == GBufferMethod::Auto || options_.method == GBufferMethod::Host) {
    resolve_hits_.emplace(device, shaders.load("gbuffer/gbuffer_resolve.vert"),
                          shaders.load("gbuffer/gbuffer_resolve.frag", "hosthits"),
                          raster_desc("gbuffer.resolve", colors, false, options_.textured));
  }
}

void GBufferPass::set_method(GBufferMethod method) {
  const bool made = method == GBufferMethod::Auto
                        ? draws_ && forward_draws_ && resolve_hits_
                        : (method == GBufferMethod::Visibility ? draws_.has_value()
                           : method == GBufferMethod::Forward  ? forward_draws_.has_value()
                                                               : resolve_hits_.has_value());
  if (!made) {
    throw InputError(fmt::format("gbuffer: made for method {}, cannot switch to {}",
                                 gbuffer_method_name(options_.method),
                                 gbuffer_method_name(method)));
  }
  options_.method = method;
}

GBufferMethod GBufferPass::method_for(GBufferMethod method, std::uint64_t triangles,
                                      std::uint32_t width, std::uint32_t height, bool host) {
  if (method != GBufferMethod::Auto) return method;
  const std::uint64_t pixels = std::uint64_t{width} * height;
  if (triangles * kForwardPixelsPerTriangle <= pixels) return GBufferMethod::Forward;
  return host && triangles >= pixels * kHostTrianglesPerPixel ? GBufferMethod::Host
                                                              : GBufferMethod::Visibility;
}

GBufferHandles GBufferPass::add_pass(RenderGraph& graph, const SceneHandles& scene,
                                     const GpuScene& gpu_scene, std::uint32_t width,
                                     std::uint32_t height, std::uint32_t instance_count) {
  const std::vector<gpu::GpuInstance>& instances = gpu_scene.data().instances;
  if (instances.size() < instance_count) {
    throw RuntimeError(fmt::format("gbuffer: {} instances drawn but the scene holds {} records",
                                   instance_count, instances.size()));
  }
  HostVisibility* host = gpu_scene.host_visibility();
  const std::uint64_t triangles =
      triangle_count(std::span<const gpu::GpuInstance>(instances.data(), instance_count));
  // Auto takes the host method only on a CPU device: on a GPU with visibility=host forced, the
  // host's rays are a comparison, not a fast path (it traces every instance of the scene).
  const bool host_fast = host != nullptr && resolve_hits_ && is_cpu_device(device_.info());
  const GBufferMethod method = method_for(options_.method, triangles, width, height, host_fast);
  if (method == GBufferMethod::Host) {
    if (host == nullptr) {
      throw InputError(
          "gbuffer: the host method needs host visibility (a CPU device and visibility=host or "
          "auto, no alpha-tested material)");
    }
    return add_host_pass(graph, scene, width, height, *host, gpu_scene.frame_constants());
  }
  return add_method(graph, scene, width, height, instance_count, triangles, method);
}

std::uint64_t GBufferPass::triangle_count(std::span<const gpu::GpuInstance> instances) {
  std::uint64_t triangles = 0;
  for (const gpu::GpuInstance& instance : instances) triangles += instance.geometry.z / 3;
  return triangles;
}

GBufferHandles GBufferPass::add_pass(RenderGraph& graph, const SceneHandles& scene,
                                     std::uint32_t width, std::uint32_t height,
                                     std::span<const gpu::GpuInstance> instances) {
  return add_pass(graph, scene, width, height, static_cast<std::uint32_t>(instances.size()),
                  triangle_count(instances));
}

GBufferHandles GBufferPass::add_pass(RenderGraph& graph, const SceneHandles& scene,
                                     std::uint32_t width, std::uint32_t height,
                                     std::uint32_t instance_count, std::uint64_t triangles) {
  return add_method(graph, scene, width, height, instance_count, triangles,
                    method_for(options_.method, triangles, width, height));
}

GBufferHandles GBufferPass::add_method(RenderGraph& graph, const SceneHandles& scene,
                                       std::uint32_t width, std::uint32_t height,
                                       std::uint32_t instance_count, std::uint64_t triangles,
                                       GBufferMethod method) {
  if (width == 0 || height == 0) {
    throw InputError(fmt::format("gbuffer: render size {}x{} must be positive", width, height));
  }
  // A scene buffer the G-buffer's shaders read but `scene` lacks: SceneHandles::declare_reads
  // throws naming it.
  if (triangles > 0xffffffffull / 3) {
    throw RuntimeError(fmt::format("gbuffer: {} triangles exceed one draw", triangles));
  }
  if (instance_count == 0) triangles = 0;
  if (method == GBufferMethod::Host) {
    throw InputError("gbuffer: the host method needs the scene's host visibility (add_pass with "
                     "its GpuScene)");
  }
  return method == GBufferMethod::Forward
             ? add_forward(graph, scene, width, height, instance_count)
             : add_visibility(graph, scene, width, height, instance_count,
                              static_cast<std::uint32_t>(triangles));
}

GBufferHandles GBufferPass::add_host_pass(RenderGraph& graph, const SceneHandles& scene,
                                          std::uint32_t width, std::uint32_t height,
                                          HostVisibility& host, const gpu::FrameConstants& frame) {
  if (!resolve_hits_) {
    throw InputError(fmt::format("gbuffer: made for method {}, not host",
                                 gbuffer_method_name(options_.method)));
  }
  if (width == 0 || height == 0) {
    throw InputError(fmt::format("gbuffer: render size {}x{} must be positive", width, height));
  }
  return resolve(graph, scene, width, height, host.add_primary_pass(graph, frame, width, height),
                 {});
}

GBufferHandles GBufferPass::add_visibility(RenderGraph& graph, const SceneHandles& scene,
                                           std::uint32_t width, std::uint32_t height,
                                           std::uint32_t instance_count, std::uint32_t triangles) {
  // Buffers are never empty (a scene without triangles still gets its draw of 0 vertices).
  const std::uint64_t capacity = std::max<std::uint64_t>(triangles, 1);
  const gpu::GBufferDrawsPush push{instance_count, static_cast<std::uint32_t>(capacity)};

  const DrawsData& d = graph.add_pass<DrawsData>(
      "gbuffer.draws", PassKind::Compute,
      [&](PassBuilder& b, DrawsData& data) {
        data.scene = scene;
        scene.declare_reads(b, *draws_);
        data.chunks =
            b.write(graph.create_buffer("gbuffer.chunks",
                                        {4 * std::uint64_t{std::max(instance_count, 1u)}}),
                    Access::StorageWrite);
        data.dispatch = b.write(graph.create_buffer("gbuffer.dispatch", {kDispatchBytes}),
                                Access::StorageWrite);
        data.draw =
            b.write(graph.create_buffer("gbuffer.draw", {kDrawCommandBytes}), Access::StorageWrite);
      },
      [this, push](PassContext& ctx, const DrawsData& data) {
        runtime::Bindings bindings(*draws_);
        data.scene.bind(bindings, ctx);
        bindings.buffer("gbuffer_chunks", ctx.buffer(data.chunks), 0, VK_WHOLE_SIZE)
            .buffer("gbuffer_dispatch", ctx.buffer(data.dispatch), 0, VK_WHOLE_SIZE)
            .buffer("gbuffer_draw", ctx.buffer(data.draw), 0, VK_WHOLE_SIZE);
        draws_->bind(ctx.cmd(), bindings);
        draws_->push_constants(ctx.cmd(), push);
        draws_->dispatch(ctx.cmd(), 1);
      });

  const CullData& c = graph.add_pass<CullData>(
      "gbuffer.cull", PassKind::Compute,
      [&](PassBuilder& b, CullData& data) {
        data.scene = scene;
        scene.declare_reads(b, *cull_);
        data.chunks = d.chunks;
        b.read(d.chunks, Access::StorageRead);
        data.dispatch = d.dispatch;
        b.read(d.dispatch, Access::IndirectBuffer);
        data.draw = b.write(d.draw, Access::StorageReadWrite);
        data.triangles =
            b.write(graph.create_buffer("gbuffer.triangles", {capacity * kTriangleRecordBytes}),
                    Access::StorageWrite);
        data.clip = b.write(graph.create_buffer("gbuffer.clip", {capacity * kTriangleClipBytes}),
                            Access::StorageWrite);
      },
      [this, push](PassContext& ctx, const CullData& data) {
        if (push.instance_count == 0) return;
        runtime::Bindings bindings(*cull_);
        data.scene.bind(bindings, ctx);
        bindings.buffer("gbuffer_chunks", ctx.buffer(data.chunks), 0, VK_WHOLE_SIZE)
            .buffer("gbuffer_triangles", ctx.buffer(data.triangles), 0, VK_WHOLE_SIZE)
            .buffer("gbuffer_clip", ctx.buffer(data.clip), 0, VK_WHOLE_SIZE)
            .buffer("gbuffer_draw", ctx.buffer(data.draw), 0, VK_WHOLE_SIZE);
        cull_->bind(ctx.cmd(), bindings);
        cull_->push_constants(ctx.cmd(), push);
        vkCmdDispatchIndirect(ctx.cmd(), ctx.buffer(data.dispatch), 0);
      });

  const VisibilityData& v = graph.add_pass<VisibilityData>(
      "gbuffer", PassKind::Graphics,
      [&](PassBuilder& b, VisibilityData& data) {
        data.scene = scene;
        scene.declare_reads(b, *raster_);
        data.triangles = c.triangles;
        b.read(c.triangles, Access::StorageRead);
        data.draw = c.draw;
        b.read(c.draw, Access::IndirectBuffer);
        data.clip = c.clip;
        b.read(c.clip, Access::StorageRead);
        data.visibility = b.write(
            graph.create_image("gbuffer.visibility", {{width, height, 1}, kVisibilityFormat}),
            Access::ColorAttachment);
        data.depth =
            b.write(graph.create_image("gbuffer.depth", {{width, height, 1}, kDepthFormat}),
                    Access::DepthAttachment);
      },
      [this, width, height](PassContext& ctx, const VisibilityData& data) {
        const VkCommandBuffer cmd = ctx.cmd();
        const std::array<runtime::ColorTarget, 1> targets = {
            runtime::ColorTarget{.view = ctx.view(data.visibility), .clear = visibility_clear()}};
        const runtime::DepthTarget depth{.view = ctx.view(data.depth), .clear = 1.0f};
        runtime::begin_rendering(device_, cmd, VkExtent2D{width, height}, targets, &depth);
        runtime::Bindings bindings(*raster_);
        data.scene.bind(bindings, ctx);
        bindings.buffer("gbuffer_clip", ctx.buffer(data.clip), 0, VK_WHOLE_SIZE)
            .buffer("gbuffer_triangles", ctx.buffer(data.triangles), 0, VK_WHOLE_SIZE);
        raster_->bind(cmd, bindings);
        vkCmdDrawIndirect(cmd, ctx.buffer(data.draw), 0, 1, kDrawCommandBytes);
        runtime::end_rendering(device_, cmd);
      });

  return resolve(graph, scene, width, height, c.triangles, v.visibility);
}

// gbuffer.resolve: from the visibility method's list (`triangles`) and gbuffer.visibility, or,
// without `visibility`, from the host method's one (instance, triangle) record per pixel.
GBufferHandles GBufferPass::resolve(RenderGraph& graph, const SceneHandles& scene,
                                    std::uint32_t width, std::uint32_t height,
                                    BufferHandle triangles, ImageHandle visibility) {
  runtime::GraphicsPipeline* pipeline = visibility.valid() ? &*resolve_ : &*resolve_hits_;
  const ResolveData& r = graph.add_pass<ResolveData>(
      "gbuffer.resolve", PassKind::Graphics,
      [&](PassBuilder& b, ResolveData& data) {
        data.scene = scene;
        scene.declare_reads(b, *pipeline);
        data.triangles = triangles;
        b.read(triangles, Access::StorageRead);
        if (visibility.valid()) {
          data.visibility = visibility;
          b.read(visibility, Access::StorageRead);
        }
        for (std::size_t i = 0; i < kColorFormats.size(); ++i) {
          data.colors[i] =
              b.write(graph.create_image(kColorNames[i], {{width, height, 1}, kColorFormats[i]}),
                      Access::ColorAttachment);
        }
      },
      [pipeline, this, width, height](PassContext& ctx, const ResolveData& data) {
        const VkCommandBuffer cmd = ctx.cmd();
        // Every pixel is written: nothing to clear or load.
        std::array<runtime::ColorTarget, 6> targets{};
        for (std::size_t i = 0; i < targets.size(); ++i) targets[i].view = ctx.view(data.colors[i]);
        runtime::begin_rendering(device_, cmd, VkExtent2D{width, height}, targets, nullptr);
        runtime::Bindings bindings(*pipeline);
        data.scene.bind(bindings, ctx);
        bindings.buffer("gbuffer_triangles", ctx.buffer(data.triangles), 0, VK_WHOLE_SIZE);
        if (data.visibility.valid()) {
          bindings.image_view("gbuffer_visibility", ctx.view(data.visibility),
                              VK_IMAGE_LAYOUT_GENERAL);
        }
        pipeline->bind(cmd, bindings);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        runtime::end_rendering(device_, cmd);
      });
  return handles(r.colors);
}

GBufferHandles GBufferPass::add_forward(RenderGraph& graph, const SceneHandles& scene,
                                        std::uint32_t width, std::uint32_t height,
                                        std::uint32_t instance_count) {
  BufferHandle draws;
  if (instance_count > 0) {
    const DrawsData& d = graph.add_pass<DrawsData>(
        "gbuffer.draws", PassKind::Compute,
        [&](PassBuilder& b, DrawsData& data) {
          data.scene = scene;
          scene.declare_reads(b, *forward_draws_);
          data.draw = b.write(graph.create_buffer("gbuffer.draws", {std::uint64_t{instance_count} *
                                                                    kDrawCommandBytes}),
                              Access::StorageWrite);
        },
        [this, instance_count](PassContext& ctx, const DrawsData& data) {
          // The culled method's outputs are unused here: bind the draw buffer in their place.
          const VkBuffer draw = ctx.buffer(data.draw);
          runtime::Bindings bindings(*forward_draws_);
          data.scene.bind(bindings, ctx);
          bindings.buffer("gbuffer_chunks", draw, 0, VK_WHOLE_SIZE)
              .buffer("gbuffer_dispatch", draw, 0, VK_WHOLE_SIZE)
              .buffer("gbuffer_draw", draw, 0, VK_WHOLE_SIZE);
          forward_draws_->bind(ctx.cmd(), bindings);
          forward_draws_->push_constants(ctx.cmd(), gpu::GBufferDrawsPush{instance_count, 0});
          forward_draws_->dispatch(ctx.cmd(), 1);
        });
    draws = d.draw;
  }

  const ForwardData& f = graph.add_pass<ForwardData>(
      "gbuffer", PassKind::Graphics,
      [&](PassBuilder& b, ForwardData& data) {
        data.scene = scene;
        scene.declare_reads(b, *forward_raster_);
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
      [this, width, height, instance_count](PassContext& ctx, const ForwardData& data) {
        const VkCommandBuffer cmd = ctx.cmd();
        std::array<runtime::ColorTarget, 6> targets{};
        for (std::size_t i = 0; i < targets.size(); ++i) {
          targets[i].view = ctx.view(data.colors[i]);
          targets[i].clear = clear_value(i);
        }
        const runtime::DepthTarget depth{.view = ctx.view(data.depth), .clear = 1.0f};
        runtime::begin_rendering(device_, cmd, VkExtent2D{width, height}, targets, &depth);
        if (instance_count > 0) {
          runtime::Bindings bindings(*forward_raster_);
          data.scene.bind(bindings, ctx);
          forward_raster_->bind(cmd, bindings);
          const VkBuffer draw_buffer = ctx.buffer(data.draws);
          for (std::uint32_t i = 0; i < instance_count; ++i) {
            forward_raster_->push_constants(cmd, gpu::GBufferPush{i});
            vkCmdDrawIndirect(cmd, draw_buffer, VkDeviceSize{i} * kDrawCommandBytes, 1,
                              kDrawCommandBytes);
          }
        }
        runtime::end_rendering(device_, cmd);
      });
  return handles(f.colors);
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
  gpu::GpuMaterial material{};
  material.textures = glm::uvec4(gpu::kNoTexture);  // the textured variant samples nothing
  const gpu::GpuTexture texture_stand_in{};
  const std::array<std::uint32_t, 4> texel_stand_in{};
  const gpu::vec4 tangent_stand_in{0.0f};
  const glm::vec2 texcoord1_stand_in{0.0f};
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
  buffers.push_back(
      make(std::span<const gpu::GpuTexture>(&texture_stand_in, 1), "warm_up.textures"));
  buffers.push_back(make(std::span<const std::uint32_t>(texel_stand_in), "warm_up.texels"));
  buffers.push_back(make(std::span<const gpu::vec4>(&tangent_stand_in, 1), "warm_up.tangents"));
  buffers.push_back(
      make(std::span<const glm::vec2>(&texcoord1_stand_in, 1), "warm_up.texcoords1"));

  RenderGraph graph;
  runtime::graph::GraphExecutor executor(device_);
  // The host method's resolve reads one record per pixel: the triangle, as Embree would name it.
  const glm::uvec2 hit(0u, 0u);
  buffers.push_back(make(std::span<const glm::uvec2>(&hit, 1), "warm_up.host_hits"));
  for (const GBufferMethod method :
       {GBufferMethod::Visibility, GBufferMethod::Forward, GBufferMethod::Host}) {
    if (options_.method != GBufferMethod::Auto && options_.method != method) continue;
    graph.begin_frame();
    runtime::graph::ImportInfo read_only;
    read_only.read_only = true;
    auto import = [&](std::size_t i) {
      return graph.import_buffer(buffers[i].name(), buffers[i].handle(), {buffers[i].size()},
                                 read_only);
    };
    SceneHandles scene;
    scene[gpu::kSceneFrameConstants] = import(0);
    scene[gpu::kSceneVertices] = import(1);
    scene[gpu::kSceneIndices] = import(2);
    scene[gpu::kSceneMaterials] = import(3);
    scene[gpu::kSceneInstances] = import(4);
    scene[gpu::kSceneTextures] = import(5);
    scene[gpu::kSceneTexels] = import(6);
    scene[gpu::kSceneVertexTangents] = import(7);
    scene[gpu::kSceneVertexTexcoords1] = import(8);
    const GBufferHandles out = method == GBufferMethod::Host
                                   ? resolve(graph, scene, 1, 1, import(9), {})
                                   : add_method(graph, scene, 1, 1, 1, 1, method);
    // Keep the passes alive: a consumer of one of their images.
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
}

}  // namespace lantern::lighting
