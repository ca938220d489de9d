// integrators.reference: reads the G-buffer and the scene (with its environment map), writes the
// HDR buffer; one workgroup per shuffled 8x8 tile, all spp samples in one dispatch
// (shaders/integrators/reference.comp).
#include "lighting/integrators/reference_integrator.h"

#include <fmt/format.h>

#include <charconv>
#include <numeric>

#include "engine/core/error.h"
#include "integrators/reference.h"
#include "lighting/scene/gpu_scene.h"
#include "runtime/gpu/bindings.h"

namespace lantern::lighting {
namespace {

using runtime::graph::Access;
using runtime::graph::BufferHandle;
using runtime::graph::ImageHandle;

// Upper bound on samples per pixel per frame (one dispatch; average frames for more).
constexpr std::uint32_t kMaxSpp = 1u << 16;

// A stride near count / golden ratio coprime to `count` (as integrators.baseline).
std::uint32_t tile_stride(std::uint32_t count) {
  if (count < 3 || count > 65535) return 1;
  auto stride = static_cast<std::uint32_t>(static_cast<double>(count) * 0.6180339887);
  while (std::gcd(stride, count) != 1) ++stride;
  return stride;
}

}  // namespace

ReferenceSettings parse_reference_settings(
    const std::vector<std::pair<std::string, std::string>>& settings, std::uint32_t spp) {
  ReferenceSettings out;
  out.spp = gpu::kReferenceDefaultSpp;
  for (const auto& [key, value] : settings) {
    if (key == "reference.spp") {
      std::uint32_t n = 0;
      const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
      if (ec != std::errc() || end != value.data() + value.size() || n == 0 || n > kMaxSpp) {
        throw InputError(
            fmt::format("--set reference.spp={}: expected an integer in 1..{}", value, kMaxSpp));
      }
      out.spp = n;
    } else {
      throw InputError(fmt::format(
          "--set {}: unknown setting for the reference integrator (known: reference.spp)", key));
    }
  }
  if (spp > kMaxSpp) {
    throw InputError(
        fmt::format("--spp {}: at most {} samples per pixel per frame (average "
                    "frames for more)",
                    spp, kMaxSpp));
  }
  if (spp != 0) out.spp = spp;
  return out;
}

ReferenceIntegrator::ReferenceIntegrator(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                         const ReferenceSettings& settings)
    : pipeline_(device, shaders.load("integrators/reference.comp"),
                runtime::ComputePipelineDesc{.name = "integrators.reference", .constants = {}}),
      settings_(settings) {
  if (settings_.spp == 0 || settings_.spp > kMaxSpp) {
    throw InputError(
        fmt::format("reference: {} samples per pixel (expected 1..{})", settings_.spp, kMaxSpp));
  }
}

ReferenceIntegrator::~ReferenceIntegrator() = default;

BufferHandle ReferenceIntegrator::add_passes(runtime::graph::RenderGraph& graph,
                                             const FrameInputs& inputs, BufferHandle hdr) {
  struct Data {
    BufferHandle hdr;
    ImageHandle position, normal, emission, ids;
  };
  const std::uint32_t width = inputs.width;
  const std::uint32_t height = inputs.height;
  gpu::ReferencePush push{};
  push.frame_index = inputs.frame_index;
  push.light_count = inputs.light_count;
  push.scene_radius = inputs.scene->scene_radius();
  const std::uint32_t tiles = ((width + gpu::kReferenceTileSize - 1) / gpu::kReferenceTileSize) *
                              ((height + gpu::kReferenceTileSize - 1) / gpu::kReferenceTileSize);
  push.tile_stride = tile_stride(tiles);
  push.spp = settings_.spp;
  const GpuScene* scene = inputs.scene;
  const Data& data = graph.add_pass<Data>(
      "integrators.reference", runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        inputs.scene_handles.declare_reads(b);
        d.position = inputs.gbuffer.position;
        d.normal = inputs.gbuffer.normal;
        d.emission = inputs.gbuffer.emission_metallic;
        d.ids = inputs.gbuffer.ids;
        for (ImageHandle h : {d.position, d.normal, d.emission, d.ids}) {
          b.read(h, Access::StorageRead);
        }
        d.hdr = b.write(hdr, Access::StorageWrite);
      },
      [this, scene, push, tiles](runtime::graph::PassContext& ctx, const Data& d) {
        runtime::Bindings bindings(pipeline_);
        scene->bind(bindings);
        bindings.buffer("radiance", ctx.buffer(d.hdr), 0, VK_WHOLE_SIZE)
            .image_view("gbuffer_position", ctx.view(d.position), VK_IMAGE_LAYOUT_GENERAL)
            .image_view("gbuffer_normal", ctx.view(d.normal), VK_IMAGE_LAYOUT_GENERAL)
            .image_view("gbuffer_emission_metallic", ctx.view(d.emission), VK_IMAGE_LAYOUT_GENERAL)
            .image_view("gbuffer_ids", ctx.view(d.ids), VK_IMAGE_LAYOUT_GENERAL);
        pipeline_.bind(ctx.cmd(), bindings);
        pipeline_.push_constants(ctx.cmd(), push);
        pipeline_.dispatch(ctx.cmd(), tiles);
      });
  return data.hdr;
}

}  // namespace lantern::lighting
