// RestirIntegrator: settings -> push constants, the frame's reservoir plan -> graph resources,
// and the passes in order.
#include "lighting/restir/restir_integrator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/error.h"
#include "lighting/frame/tile_order.h"
#include "lighting/scene/gpu_scene.h"
#include "lighting/visibility/host_visibility.h"
#include "lighting/visibility/visibility_backend.h"
#include "runtime/core/device.h"
#include "shared/pixel_groups.h"
#include "shared/reservoir_pack.h"

namespace lantern::lighting {

using runtime::graph::Access;
using runtime::graph::BufferHandle;

RestirIntegrator::RestirIntegrator(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                   const RestirSettings& settings, VisibilityBackend visibility)
    : device_(device),
      shaders_(shaders),
      settings_(settings),
      visibility_(visibility),
      tile_bands_(tile_bands(is_cpu_device(device.info()))),
      presample_(device, shaders, "presample"),
      initial_(device, shaders, "initial", visibility),
      temporal_(device, shaders, "temporal"),
      spatial_(device, shaders, "spatial"),
      shade_(device, shaders, "shade", visibility) {}

void RestirIntegrator::warm_up() {
  // With host visibility the BVH's restir.shade never runs: its two variants are JIT-compiled
  // instead, and restir.initial's two when the settings draw BSDF candidates.
  std::vector<const runtime::ComputePipeline*> pipelines{&presample_.pipeline(),
                                                         &temporal_.pipeline(),
                                                         &spatial_.pipeline()};
  if (host_) {
    pipelines.push_back(&shade_emit_->pipeline());
    pipelines.push_back(&shade_occluded_->pipeline());
  } else {
    pipelines.push_back(&shade_.pipeline());
  }
  if (host_traces_bsdf(settings_.bsdf_candidates)) {
    pipelines.push_back(&initial_rays_->pipeline());
    pipelines.push_back(&initial_closest_->pipeline());
  } else {
    pipelines.push_back(&initial_.pipeline());
  }
  runtime::warm_up(device_, pipelines);
  if (volume_) runtime::warm_up(device_, volume_->pipelines());
}

void RestirIntegrator::apply_settings(
    const std::vector<std::pair<std::string, std::string>>& changes) {
  RestirSettings next = settings_;
  for (const auto& [key, value] : changes) apply_setting(next, key, value);
  settings_ = next;
}

std::vector<std::pair<std::string, double>> RestirIntegrator::shadow_rays_per_pixel() const {
  std::vector<std::pair<std::string, double>> rays{
      {host_ != nullptr ? "visibility.host" : "restir.shade", 1.0}};
  if (settings_.initial_visibility) rays.emplace_back("restir.initial", 1.0);
  return rays;
}

float RestirIntegrator::light_spread(const RestirSettings& s, const FrameInputs& inputs) {
  if (s.light_spread >= 0.0f) return s.light_spread;
  // Not measured: as if every light lit only its surroundings (the count rules alone).
  return inputs.light_spread.value_or(std::numeric_limits<float>::max());
}

std::uint32_t RestirIntegrator::presample_tiles(const RestirSettings& s,
                                               const FrameInputs& inputs) {
  // Presampling pays off only when a tile is smaller than the light list, and only while the
  // presampled entries stay a small part of the candidates drawn from them (at most 1/8: at
  // 160x90, 32 tiles made the frame slower than the alias table).
  if (s.presample_tiles == 0 || inputs.light_count <= gpu::kRestirPresampleTileSize) return 0;
  const std::uint64_t draws =
      std::uint64_t{inputs.width} * inputs.height * s.light_candidates;
  const std::uint64_t affordable = draws / (8 * std::uint64_t{gpu::kRestirPresampleTileSize});
  // More tiles than the light spread buy nothing: together T tiles of power draws estimate the
  // light at a surface with relative variance spread / (T * tile size), at most 1 / tile size
  // once T >= spread, and every further tile only adds records for the passes to read in no
  // order (light_panels: 4.1, 5 tiles instead of 32; night_market: 60, all 32).
  const auto wanted = static_cast<std::uint64_t>(
      std::ceil(std::min<double>(light_spread(s, inputs), s.presample_tiles)));
  return static_cast<std::uint32_t>(
      std::clamp<std::uint64_t>(std::min(affordable, wanted), 1, s.presample_tiles));
}

bool RestirIntegrator::lights_local(const RestirSettings& s, const FrameInputs& inputs) {
  return inputs.light_count >= s.local_min_lights &&
         light_spread(s, inputs) >= kLocalListsMinSpread;
}

std::uint32_t RestirIntegrator::local_candidates(const RestirSettings& s,
                                                 const FrameInputs& inputs) {
  // Local lists pay off where lights are many (RestirSettings::local_min_lights) and each lights
  // only its surroundings (a spread of at least kLocalListsMinSpread).
  return lights_local(s, inputs) ? s.local_candidates : 0u;
}

std::uint32_t RestirIntegrator::grid_candidates(const RestirSettings& s,
                                                const FrameInputs& inputs) {
  // Where power draws and the local lists already find every light (few lights, or lights that
  // light everything alike) a light beside the surface is no rarer than any other.
  return lights_local(s, inputs) ? s.grid_candidates : 0u;
}

std::uint32_t RestirIntegrator::bsdf_candidates(const RestirSettings& s,
                                                const FrameInputs& inputs) {
  return inputs.max_gloss >= s.bsdf_min_gloss ? s.bsdf_candidates : 0u;
}

namespace {

// With one reservoir per stride x stride pixels, this frame's offset of each cell's representative
// pixel (RestirPush::representative: x | y << 16): every offset once in stride^2 frames,
// (x, y) = (k mod stride, (k / stride + k) mod stride), so consecutive frames move diagonally.
std::uint32_t representative_offset(std::uint32_t stride, std::uint64_t frame_index) {
  if (stride <= 1) return 0;
  const auto k = static_cast<std::uint32_t>(frame_index % (std::uint64_t{stride} * stride));
  return (k % stride) | (((k / stride + k) % stride) << 16);
}

}  // namespace

gpu::RestirPush RestirIntegrator::make_push(const RestirSettings& s, const FrameInputs& inputs) {
  if (inputs.light_count >= gpu::kEnvironmentLight) {
    throw InputError(fmt::format("restir: {} lights exceed the {} a packed reservoir can index",
                                 inputs.light_count, gpu::kEnvironmentLight));
  }
  gpu::RestirPush p{};
  p.flags = s.initial_visibility ? gpu::kRestirFlagInitialVisibility : 0u;
  if (s.temporal_permutation == kTemporalPermutationOn ||
      (s.temporal_permutation == kTemporalPermutationDenoised && inputs.denoised)) {
    p.flags |= gpu::kRestirFlagTemporalPermutation;
    p.permutation_bits = gpu::restir_permutation_bits(inputs.frame_index, inputs.seed);
  }
  p.light_candidates = s.light_candidates;
  p.bsdf_candidates = bsdf_candidates(s, inputs);
  p.grid_candidates = grid_candidates(s, inputs);
  p.bsdf_min_gloss = s.bsdf_min_gloss;
  p.bias_correction = s.bias_correction;
  p.debug_view = s.debug_view;
  p.neighbours = s.neighbours;
  p.boost_neighbours = s.disocclusion_boost;
  p.temporal_neighbours = s.temporal_neighbours;
  // The candidates this frame draws (none from BSDFs where the level has no surface for them).
  const std::uint32_t drawn = s.light_candidates + p.bsdf_candidates + p.grid_candidates;
  p.short_history_m = 2 * drawn;
  p.radius = s.radius;
  p.m_cap = s.m_cap(drawn);
  // A lower cap where points move only where the denoiser averages the frames (RestirSettings).
  p.m_cap_moving = inputs.denoised ? s.m_cap_moving : 1.0f;
  p.boiling_filter = s.boiling_filter;
  p.presample_tiles = presample_tiles(s, inputs);
  p.local_candidates = local_candidates(s, inputs);
  // A verdict is one pixel's: none kept where pixels share a reservoir (make_restir_settings
  // refuses the pair; the play panel can still set it).
  p.visibility_reuse = s.temporal && s.reservoir_stride == 1 ? s.visibility_reuse : 0u;
  p.reservoir_stride = s.reservoir_stride;
  p.representative = representative_offset(s.reservoir_stride, inputs.frame_index);
  p.similarity = {s.depth_threshold, s.normal_threshold, 0.25f, 0.0f};
  return p;
}

namespace {

// A transfer pass filling `buffer` with the 32-bit `value`; returns its new version.
BufferHandle clear_buffer(runtime::graph::RenderGraph& graph, const char* name,
                          BufferHandle buffer, std::uint32_t value) {
  struct Clear {
    BufferHandle buffer;
  };
  return graph
      .add_pass<Clear>(
          name, runtime::graph::PassKind::Transfer,
          [&](runtime::graph::PassBuilder& b, Clear& d) {
            d.buffer = b.write(buffer, Access::TransferDst);
          },
          [value](runtime::graph::PassContext& ctx, const Clear& d) {
            vkCmdFillBuffer(ctx.cmd(), ctx.buffer(d.buffer), 0, VK_WHOLE_SIZE, value);
          })
      .buffer;
}

}  // namespace

BufferHandle RestirIntegrator::add_passes(runtime::graph::RenderGraph& graph,
                                          const FrameInputs& inputs, BufferHandle hdr) {
  const RestirSettings s = settings_;
  gpu::RestirPush push = make_push(s, inputs);
  confidence_ = {};
  const VkDeviceSize pixels = VkDeviceSize{inputs.width} * inputs.height;
  // The reservoir grid: one cell per push.reservoir_stride^2 pixels (RestirSettings).
  const std::uint32_t stride = push.reservoir_stride;
  const glm::uvec2 grid = gpu::restir_grid_extent({inputs.width, inputs.height}, stride);
  const VkDeviceSize cells = VkDeviceSize{grid.x} * grid.y;
  const runtime::graph::BufferDesc reservoir_desc{cells * sizeof(gpu::PackedReservoir)};

  // History resources: this frame's versions, and last frame's when reuse is possible. The
  // surfaces are the cells' (each its representative pixel's).
  BufferHandle surfaces = graph.create_history_buffer(
      "restir.surfaces", {cells * sizeof(gpu::RestirSurface)});
  // Every pixel's surface, for restir.shade, written by restir.initial beside the cells'; with
  // one reservoir per pixel the cells' own (then a one-surface stand-in, not written, is bound).
  BufferHandle pixel_surfaces = graph.create_buffer(
      "restir.pixel_surfaces", {(stride > 1 ? pixels : 1) * sizeof(gpu::RestirSurface)});
  BufferHandle final_reservoirs = graph.create_history_buffer("restir.reservoirs", reservoir_desc);
  BufferHandle surfaces_history;
  BufferHandle reservoirs_history;
  // A light removed since last frame: every history sample's W still carries that light's share
  // of its resampling weight, so reusing any of them biases the frame (measured on a 100:1 light
  // pair: +114..175% persisting for frames when only the removed light's samples are dropped,
  // -20% when their confidence is kept). Lights disappear rarely; skip reuse for one frame.
  const bool lights_removed = inputs.previous_light_count > inputs.light_count;
  if (s.temporal && !lights_removed) {
    surfaces_history = graph.history(surfaces);
    reservoirs_history = graph.history(final_reservoirs);
  }
  const bool history = surfaces_history.valid() && reservoirs_history.valid();
  if (history) push.flags |= gpu::kRestirFlagHistoryValid;

  const std::vector<ReservoirStep> plan = buffers_.next_frame({.temporal = s.temporal,
                                                               .spatial_passes = s.spatial_passes,
                                                               .history_valid = history});

  // Latest version of each buffer the plan names.
  BufferHandle scratch_a;
  BufferHandle scratch_b;
  auto handle = [&](ReservoirBuffer id) -> BufferHandle& {
    switch (id) {
      case ReservoirBuffer::ScratchA:
        if (!scratch_a) scratch_a = graph.create_buffer("restir.reservoirs.a", reservoir_desc);
        return scratch_a;
      case ReservoirBuffer::ScratchB:
        if (!scratch_b) scratch_b = graph.create_buffer("restir.reservoirs.b", reservoir_desc);
        return scratch_b;
      case ReservoirBuffer::Final:
        return final_reservoirs;
      case ReservoirBuffer::History:
        return reservoirs_history;
      case ReservoirBuffer::None:
        break;
    }
    throw RuntimeError("restir: the reservoir plan names no buffer where one is needed");
  };

  BufferHandle status =
      graph.create_buffer("restir.temporal_status", {cells * sizeof(std::uint32_t)});
  bool status_written = false;
  for (const ReservoirStep& step : plan) {
    switch (step.stage) {
      case ReservoirStage::Initial: {
        // restir.presample (when on): push.presample_tiles tiles of lights drawn from the alias
        // table, with copies of their records. Off, a one-entry stand-in is bound (not read).
        const std::uint32_t entries = push.presample_tiles * gpu::kRestirPresampleTileSize;
        BufferHandle presampled = graph.create_buffer(
            "restir.presampled_lights",
            {std::max<VkDeviceSize>(entries, 1) * sizeof(gpu::PresampledLight)});
        if (entries > 0) {
          const std::uint32_t per_group = gpu::kPixelGroupThreads;
          presampled = presample_.add(graph, inputs, push,
                                      {{"presampled_lights", presampled,
                                        RestirPass::Buffer::Write}},
                                      (entries + per_group - 1) / per_group)[0];
        } else {
          presampled = clear_buffer(graph, "restir.clear_presampled", presampled, 0u);
        }
        // restir.initial: the G-buffer packed into RestirSurfaces (this frame's version of the
        // "restir.surfaces" history) and each pixel's initial reservoir from light (and BSDF)
        // candidates. Reads the G-buffer and the scene (lights, alias table, materials, BVH).
        std::vector<BufferHandle> out;
        if (host_traces_bsdf(push.bsdf_candidates)) {
          // Host visibility: the BSDF candidates' rays are written by restir.initial_rays,
          // traced by visibility.host_closest, and their hits read by restir.initial.
          const BufferHandle hits = host_->add_closest_rays(
              graph, static_cast<std::uint32_t>(cells * push.bsdf_candidates),
              [&](BufferHandle empty) {
                return initial_rays_->add(
                    graph, inputs, push,
                    {{"host_closest_rays", empty, RestirPass::Buffer::Write}})[0];
              });
          out = initial_closest_->add(
              graph, inputs, push,
              {{"restir_surfaces", surfaces, RestirPass::Buffer::Write},
               {"reservoirs_out", handle(step.write), RestirPass::Buffer::Write},
               {"presampled_lights", presampled},
               {"host_closest_rays", hits},
               {"pixel_surfaces", pixel_surfaces, RestirPass::Buffer::Write}});
        } else {
          out = initial_.add(graph, inputs, push,
                             {{"restir_surfaces", surfaces, RestirPass::Buffer::Write},
                              {"reservoirs_out", handle(step.write), RestirPass::Buffer::Write},
                              {"presampled_lights", presampled},
                              {"pixel_surfaces", pixel_surfaces, RestirPass::Buffer::Write}});
        }
        surfaces = out[0];
        handle(step.write) = out[1];
        pixel_surfaces = stride > 1 ? out[2] : surfaces;
        break;
      }
      case ReservoirStage::Temporal: {
        // restir.temporal: each pixel's reservoir merged with last frame's final reservoir at its
        // reprojected pixel (and temporal_neighbours more around it) after the disocclusion test
        // and the light remap; M capped. Without history this frame's surfaces and reservoirs
        // stand in for the history bindings (the shader does not read them:
        // kRestirFlagHistoryValid is clear).
        const bool reuse = step.history == ReservoirBuffer::History;
        gpu::RestirPush p = push;
        p.tile_bands = tile_bands_;
        if (!reuse) p.flags &= ~gpu::kRestirFlagHistoryValid;
        const BufferHandle reservoirs_in = handle(step.read);
        const std::vector<BufferHandle> out = temporal_.add(
            graph, inputs, p,
            {{"restir_surfaces", surfaces},
             {"reservoirs_in", reservoirs_in},
             {"surfaces_history", reuse ? surfaces_history : surfaces},
             {"reservoirs_history", reuse ? reservoirs_history : reservoirs_in},
             {"reservoirs_out", handle(step.write), RestirPass::Buffer::Write},
             {"temporal_status", status, RestirPass::Buffer::Write}});
        handle(step.write) = out[0];
        status = out[1];
        status_written = true;
        break;
      }
      case ReservoirStage::Spatial: {
        // restir.spatial (N passes): each pixel's reservoir merged with up to k similar
        // neighbours in a disk (more where history is short); the last writes Final.
        gpu::RestirPush p = push;
        p.tile_bands = tile_bands_;
        p.spatial_pass = step.spatial_index;
        handle(step.write) = spatial_.add(graph, inputs, p,
                                          {{"restir_surfaces", surfaces},
                                           {"reservoirs_in", handle(step.read)},
                                           {"reservoirs_out", handle(step.write),
                                            RestirPass::Buffer::Write}})[0];
        break;
      }
      case ReservoirStage::Shade: {
        if (!status_written) {
          // No temporal pass: every pixel is "no history" for the disocclusion view.
          status = clear_buffer(graph, "restir.clear_status", status, gpu::kRestirStatusNoHistory);
        }
        // restir.shade: one visibility ray towards the final reservoir's sample per pixel (none
        // where visibility reuse trusts the history's verdict): emission + BRDF x Le x G x W (or
        // a debug view) into hdr. It writes each verdict back into the final reservoirs (the
        // next frame's history).
        if (host_ == nullptr) {
          const std::vector<BufferHandle> out =
              shade_.add(graph, inputs, push,
                         {{"restir_surfaces", pixel_surfaces},
                          {"reservoirs_in", handle(step.read), RestirPass::Buffer::ReadWrite},
                          {"temporal_status", status},
                          {"hdr", hdr, RestirPass::Buffer::Write}});
          handle(step.read) = out[0];
          hdr = out[1];
          confidence_ = stride == 1 ? handle(step.read) : BufferHandle{};
          break;
        }
        // Host visibility: restir.shade shades as if every ray got through and writes the rays,
        // visibility.host traces them, restir.shade_occluded rewrites the blocked pixels
        // (lighting/visibility/host_visibility.h).
        const BufferHandle rays = host_->add_shadow_rays(
            graph, static_cast<std::uint32_t>(pixels), [&](BufferHandle empty) {
              const std::vector<BufferHandle> shaded =
                  shade_emit_->add(graph, inputs, push,
                                   {{"restir_surfaces", pixel_surfaces},
                                    {"reservoirs_in", handle(step.read)},
                                    {"temporal_status", status},
                                    {"host_rays", empty, RestirPass::Buffer::Write},
                                    {"hdr", hdr, RestirPass::Buffer::Write}});
              hdr = shaded[1];
              return shaded[0];
            });
        const std::vector<BufferHandle> out = shade_occluded_->add(
            graph, inputs, push,
            {{"reservoirs_in", handle(step.read), RestirPass::Buffer::ReadWrite},
             {"host_rays", rays},
             {"hdr", hdr, RestirPass::Buffer::ReadWrite}});
        handle(step.read) = out[0];
        hdr = out[1];
        confidence_ = stride == 1 ? handle(step.read) : BufferHandle{};
        break;
      }
    }
  }
  // The media along camera rays (levels with volumes): their own reservoirs, after the surfaces.
  if (volume_) hdr = volume_->add_passes(graph, inputs, s, hdr);
  return hdr;
}

void RestirIntegrator::prepare(const GpuScene& scene) {
  host_ = scene.host_visibility();
  if (host_ != nullptr && !shade_emit_) {
    shade_emit_ =
        std::make_unique<RestirPass>(device_, shaders_, "restir.shade", "shade", "hostemit");
    shade_occluded_ = std::make_unique<RestirPass>(device_, shaders_, "restir.shade_occluded",
                                                   "shade", "hostresolve");
  }
  if (scene.volume_count() > 0 && !volume_) {
    volume_ = std::make_unique<VolumeRestir>(device_, shaders_, visibility_);
  }
}

bool RestirIntegrator::host_traces_bsdf(std::uint32_t bsdf_candidates) {
  if (host_ == nullptr || bsdf_candidates == 0) return false;
  if (initial_rays_) return true;
  initial_rays_ =
      std::make_unique<RestirPass>(device_, shaders_, "restir.initial_rays", "initial", "closestemit");
  initial_closest_ = std::make_unique<RestirPass>(device_, shaders_, "restir.initial", "initial",
                                                  "closestresolve");
  return true;
}

}  // namespace lantern::lighting
