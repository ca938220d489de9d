// integrators.reference: reads the G-buffer and the scene (with its environment map), writes the
// HDR buffer; one workgroup per shuffled tile of the device's pixel group shape, all spp samples
// in one dispatch (shaders/integrators/reference.comp).
#include "lighting/integrators/reference_integrator.h"

#include <fmt/format.h>

#include <charconv>

#include "engine/core/error.h"
#include "integrators/reference.h"
#include "lighting/frame/tile_order.h"
#include "lighting/integrators/gbuffer_shading_pass.h"
#include "lighting/scene/gpu_scene.h"

namespace lantern::lighting {
namespace {

using runtime::graph::BufferHandle;

// Upper bound on samples per pixel per frame (one dispatch; average frames for more).
constexpr std::uint32_t kMaxSpp = 1u << 16;

}  // namespace

void apply_reference_setting(ReferenceSettings& settings, std::string_view key,
                             std::string_view value) {
  if (key != "spp" && key != "reference.spp") {
    throw InputError(
        fmt::format("--set {}: unknown setting for the reference integrator (known: spp)", key));
  }
  std::uint32_t n = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
  if (ec != std::errc() || end != value.data() + value.size() || n == 0 || n > kMaxSpp) {
    throw InputError(fmt::format("--set {}={}: expected an integer in 1..{}", key, value, kMaxSpp));
  }
  settings.spp = n;
}

ReferenceSettings parse_reference_settings(
    const std::vector<std::pair<std::string, std::string>>& settings, std::uint32_t spp) {
  ReferenceSettings out;
  out.spp = gpu::kReferenceDefaultSpp;
  for (const auto& [key, value] : settings) apply_reference_setting(out, key, value);
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
                                         const ReferenceSettings& settings,
                                         VisibilityBackend visibility)
    : visibility_(visibility),
      pipeline_(device, shaders.load("integrators/reference.comp", visibility_variant(visibility)),
                runtime::ComputePipelineDesc{
                    .name = "integrators.reference",
                    .constants = pixel_group_constants(device)}),
      settings_(settings) {
  if (settings_.spp == 0 || settings_.spp > kMaxSpp) {
    throw InputError(
        fmt::format("reference: {} samples per pixel (expected 1..{})", settings_.spp, kMaxSpp));
  }
}

ReferenceIntegrator::~ReferenceIntegrator() = default;

std::vector<std::pair<std::string, std::string>> ReferenceIntegrator::describe_settings() const {
  return {{"spp", std::to_string(settings_.spp)}};
}

void ReferenceIntegrator::apply_settings(
    const std::vector<std::pair<std::string, std::string>>& changes) {
  ReferenceSettings next = settings_;
  for (const auto& [key, value] : changes) apply_reference_setting(next, key, value);
  settings_ = next;
}

BufferHandle ReferenceIntegrator::add_passes(runtime::graph::RenderGraph& graph,
                                             const FrameInputs& inputs, BufferHandle hdr) {
  const std::uint32_t width = inputs.width;
  const std::uint32_t height = inputs.height;
  gpu::ReferencePush push{};
  const std::uint32_t tiles = tile_count(width, height, pipeline_);
  push.tile_stride = tile_stride(tiles);
  push.spp = settings_.spp;
  return add_gbuffer_shading_pass(graph, "integrators.reference", pipeline_, inputs, push, tiles,
                                  hdr);
}

}  // namespace lantern::lighting
