// volume.camera: the media along camera rays (volume_camera_pass.h).
#include "lighting/volume/volume_camera_pass.h"

#include <algorithm>

#include "shared/volume.h"

namespace lantern::lighting {

VolumeCameraPass::VolumeCameraPass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                   VisibilityBackend visibility)
    : pass_(device, shaders, "volume.camera", "volume/volume_camera.comp",
            visibility_variant(visibility)) {}

runtime::graph::BufferHandle VolumeCameraPass::add_pass(runtime::graph::RenderGraph& graph,
                                                        const FrameInputs& inputs,
                                                        runtime::graph::BufferHandle hdr,
                                                        VolumeCameraSampling sampling) const {
  gpu::VolumePush push{};
  push.width = inputs.width;
  push.height = inputs.height;
  push.samples = std::max(sampling.samples, 1u);
  push.flags = sampling.phase_mis ? gpu::kVolumePushPhaseMis : 0u;
  return pass_.add(graph, inputs, push, {{"radiance", hdr, ShaderPassBuffer::ReadWrite}},
                   {.x = inputs.width, .y = inputs.height, .threads = true})[0];
}

}  // namespace lantern::lighting
