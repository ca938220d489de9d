// ReSTIR for the media: reservoirs of the light scattered into each pixel's camera ray
// (shared/volume_restir.h), the media counterpart of restir.* for levels with volumes.
// RestirIntegrator runs it after its surface passes, in place of volume.camera:
//   volume.restir_initial  RIS over (medium, distance, light) candidates + temporal reuse at the
//                          reprojected scattering point -> "volume.reservoirs.a" (transient)
//   volume.restir_spatial  spatial reuse + unbiased final shading (transmittances, shadow ray)
//                          -> "volume.reservoirs" (history: next frame's temporal input), hdr
// Both pipelines are loaded for the integrator's visibility backend.
#pragma once

#include <array>

#include "lighting/frame/frame_inputs.h"
#include "lighting/frame/shader_pass.h"
#include "lighting/restir/restir_settings.h"
#include "lighting/visibility/visibility_backend.h"
#include "runtime/runtime_fwd.h"

namespace lantern::lighting {

class VolumeRestir {
 public:
  VolumeRestir(runtime::Device& device, runtime::ShaderLibrary& shaders,
               VisibilityBackend visibility);
  // Adds both passes; returns the new version of `hdr` (the surfaces' radiance, attenuated and
  // with the in-scattered light added). Knobs: settings.volume, and the surfaces'
  // bias_correction for the spatial MIS weights.
  [[nodiscard]] runtime::graph::BufferHandle add_passes(runtime::graph::RenderGraph& graph,
                                                        const FrameInputs& inputs,
                                                        const RestirSettings& settings,
                                                        runtime::graph::BufferHandle hdr) const;
  std::array<const runtime::ComputePipeline*, 2> pipelines() const {
    return {&initial_.pipeline(), &spatial_.pipeline()};
  }

 private:
  ShaderPass initial_;
  ShaderPass spatial_;
};

}  // namespace lantern::lighting
