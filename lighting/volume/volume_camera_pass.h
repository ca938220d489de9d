// volume.camera (shaders/volume/volume_camera.comp): the media along every pixel's camera ray,
// applied in place to the integrator's radiance: the transmittance to the surface (or the sky)
// and the in-scattered light of single scattering from every light kind. FrameRenderer adds it
// after the integrator exactly when the level has volumes, so every integrator's image is seen
// through the same media and a level without volumes runs no volume pass. It traces shadow rays:
// its shader is loaded for the integrator's visibility backend.
#pragma once

#include "lighting/frame/frame_inputs.h"
#include "lighting/frame/shader_pass.h"
#include "lighting/visibility/visibility_backend.h"
#include "runtime/runtime_fwd.h"

namespace lantern::lighting {

class VolumeCameraPass {
 public:
  VolumeCameraPass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                   VisibilityBackend visibility);
  // Returns the new version of `hdr` (inputs.width x inputs.height vec4 radiance), estimated
  // as the integrator asks (Integrator::volume_sampling).
  [[nodiscard]] runtime::graph::BufferHandle add_pass(runtime::graph::RenderGraph& graph,
                                                      const FrameInputs& inputs,
                                                      runtime::graph::BufferHandle hdr,
                                                      VolumeCameraSampling sampling) const;
  // JIT-compiles the pipeline now (lavapipe compiles at first dispatch).
  void warm_up() const { pass_.pipeline().warm_up(); }

 private:
  ShaderPass pass_;
};

}  // namespace lantern::lighting
