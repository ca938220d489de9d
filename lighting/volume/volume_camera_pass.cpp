// volume.camera: the camera rays' transmittance (volume_camera_pass.h).
#include "lighting/volume/volume_camera_pass.h"

#include "shared/volume.h"

namespace lantern::lighting {

VolumeCameraPass::VolumeCameraPass(runtime::Device& device, runtime::ShaderLibrary& shaders)
    : pass_(device, shaders, "volume.camera", "volume/volume_camera.comp") {}

runtime::graph::BufferHandle VolumeCameraPass::add_pass(runtime::graph::RenderGraph& graph,
                                                        const FrameInputs& inputs,
                                                        runtime::graph::BufferHandle hdr) const {
  gpu::VolumePush push{};
  push.width = inputs.width;
  push.height = inputs.height;
  return pass_.add(graph, inputs, push, {{"radiance", hdr, ShaderPassBuffer::ReadWrite}},
                   {.x = inputs.width, .y = inputs.height, .threads = true})[0];
}

}  // namespace lantern::lighting
