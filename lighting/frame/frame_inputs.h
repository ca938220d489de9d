// What one frame hands to the lighting integrators (baseline, reference, restir): the snapshot,
// the scene buffers and G-buffer as render-graph handles, and the linear HDR target they write.
// The frame renderer (lighting/frame/frame_renderer.h) builds it after scene.upload and gbuffer;
// an Integrator adds its passes from it. Handles are valid for the current graph frame only.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/world/frame_snapshot.h"
#include "lighting/scene/scene_buffers.h"
#include "lighting/visibility/visibility_backend.h"
#include "runtime/graph/render_graph.h"

namespace lantern::lighting {

class GpuScene;

// The G-buffer images of shaders/shared/gbuffer.h, after the gbuffer pass wrote them.
struct GBufferHandles {
  runtime::graph::ImageHandle position;
  runtime::graph::ImageHandle normal;
  runtime::graph::ImageHandle albedo_roughness;
  runtime::graph::ImageHandle emission_metallic;
  runtime::graph::ImageHandle ids;
  runtime::graph::ImageHandle motion;

  // Declares a StorageRead of every image the pipeline's shaders use (imageLoad, layout GENERAL),
  // found by its GLSL name: gbuffer_position, gbuffer_normal, gbuffer_albedo_roughness,
  // gbuffer_emission_metallic, gbuffer_ids, gbuffer_motion.
  void declare_reads(runtime::graph::PassBuilder& builder, const runtime::Pipeline& pipeline) const;
  // Binds those images by the same names.
  void bind(runtime::Bindings& bindings, const runtime::graph::PassContext& ctx) const;
};

struct FrameInputs {
  const FrameSnapshot* snapshot = nullptr;
  const GpuScene* scene = nullptr;  // the CPU side of `scene_handles` (counts, radius)
  SceneHandles scene_handles;
  GBufferHandles gbuffer;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t frame_index = 0;  // frames rendered since the renderer was created
  std::uint32_t seed = 1;
  // Temporal history is the graph's: graph.history(h) is invalid on the first frame, after a
  // camera cut and after a resize (FrameRenderer invalidates it), so passes ask the graph.
  std::uint32_t light_count = 0;           // current lights (alias table size)
  std::uint32_t previous_light_count = 0;  // entries of light_previous_to_current
  // The level's light spread (SceneData::light_spread, measured at load); unset where nobody
  // measured it or no light reached a surface then (ReSTIR then decides by the light count
  // alone).
  std::optional<float> light_spread;
  // The glossiest any surface of the level can be (SceneData::max_gloss; 1 where unknown):
  // ReSTIR skips BSDF candidates that no surface would draw (RestirSettings::bsdf_min_gloss).
  float max_gloss = 1.0f;
  // The denoiser consumes this frame's radiance (FrameOutput::Denoised with the denoiser on):
  // an integrator may then trade raw noise for errors a denoiser averages better
  // (RestirSettings::temporal_permutation).
  bool denoised = false;
};

// Samples per pixel per frame of volume.camera (transmittance and in-scattering, >= 1), and
// whether each adds a phase-sampled estimate MIS'd with the light-sampled one.
struct VolumeCameraSampling {
  std::uint32_t samples = 1;
  bool phase_mis = false;
};

// A lighting integrator: adds its passes to the frame's graph. They write linear radiance into
// `hdr` (a buffer of width*height vec4, row-major from the top-left, alpha 1) and the new version
// of `hdr` is returned. Pass names are module.stage ("integrators.baseline", "restir.initial").
class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual const char* name() const = 0;
  // JIT-compiles every pipeline now (lavapipe compiles at first dispatch), not in a timed frame.
  virtual void warm_up() = 0;
  // Shadow (visibility) rays each of its passes traces per pixel, e.g. {"restir.shade", 1}:
  // what `lantern bench` divides by pass time for rays per second. Empty: not reported.
  virtual std::vector<std::pair<std::string, double>> shadow_rays_per_pixel() const { return {}; }
  // Its settings as `--set KEY=VALUE` pairs: every key with its current value (empty: none).
  virtual std::vector<std::pair<std::string, std::string>> describe_settings() const = 0;
  // Changes settings from the next frame on; lantern::InputError naming a bad key or value, and
  // then nothing changes. How play edits the running integrator without knowing its type.
  virtual void apply_settings(const std::vector<std::pair<std::string, std::string>>& changes) = 0;
  // The visibility backend its tracing passes' shaders were loaded for: the FrameRenderer builds
  // the scene to match (a TLAS for ray query).
  virtual VisibilityBackend visibility() const { return VisibilityBackend::Bvh; }
  // Called once by the FrameRenderer with the scene it built, before warm_up: where an
  // integrator creates the passes its content needs (ReSTIR: media reservoirs for volumes).
  virtual void prepare(const GpuScene& /*scene*/) {}
  // True when its own passes render the media (transmittance and in-scattering along camera
  // rays) for the prepared scene; otherwise the FrameRenderer adds volume.camera after it.
  virtual bool renders_media() const { return false; }
  // How volume.camera estimates the media along camera rays for it (lighting/volume/): one
  // light-sampled estimate per pixel for the real-time integrators; spp, each with light/phase
  // MIS, for the reference.
  virtual VolumeCameraSampling volume_sampling() const { return {}; }
  [[nodiscard]] virtual runtime::graph::BufferHandle add_passes(
      runtime::graph::RenderGraph& graph, const FrameInputs& inputs,
      runtime::graph::BufferHandle hdr) = 0;
  // After add_passes, for this frame's graph: width*height PackedReservoirs
  // (shared/reservoir_pack.h) whose M is how many candidates stand behind each pixel's sample,
  // which the denoiser weighs the frame's pixel by in its temporal accumulation; invalid (the
  // default) when every frame's pixel is worth the same.
  virtual runtime::graph::BufferHandle sample_confidence() const { return {}; }
};

}  // namespace lantern::lighting
