// VolumeRestir: the media reservoirs' two passes and their history (volume_restir.h).
#include "lighting/volume/volume_restir.h"

#include "shared/volume.h"
#include "shared/volume_restir.h"

namespace lantern::lighting {

using runtime::graph::BufferHandle;

VolumeRestir::VolumeRestir(runtime::Device& device, runtime::ShaderLibrary& shaders,
                           VisibilityBackend visibility)
    : initial_(device, shaders, "volume.restir_initial", "volume/volume_restir_initial.comp",
               visibility_variant(visibility)),
      spatial_(device, shaders, "volume.restir_spatial", "volume/volume_restir_spatial.comp",
               visibility_variant(visibility)) {}

BufferHandle VolumeRestir::add_passes(runtime::graph::RenderGraph& graph,
                                      const FrameInputs& inputs,
                                      const RestirSettings& restir,
                                      BufferHandle hdr) const {
  const RestirSettings::Volume& settings = restir.volume;
  const VkDeviceSize pixels = VkDeviceSize{inputs.width} * inputs.height;
  const runtime::graph::BufferDesc desc{pixels * sizeof(gpu::VolumeReservoir)};
  BufferHandle final_reservoirs = graph.create_history_buffer("volume.reservoirs", desc);
  BufferHandle history;
  // A light removed since last frame: its share of every history W would bias the frame (the
  // surfaces' rule, restir_integrator.cpp); skip reuse for one frame.
  if (settings.temporal && inputs.previous_light_count <= inputs.light_count) {
    history = graph.history(final_reservoirs);
  }
  gpu::VolumeRestirPush push{};
  push.width = inputs.width;
  push.height = inputs.height;
  push.candidates = settings.candidates;
  push.flags = history.valid() ? gpu::kVolumeRestirFlagHistoryValid : 0u;
  push.neighbours = settings.neighbours;
  push.radius = settings.radius;
  push.m_cap = settings.m_cap();
  push.bias_correction = restir.bias_correction;
  const ShaderPassDispatch dispatch{.x = inputs.width, .y = inputs.height, .threads = true};

  BufferHandle scratch = graph.create_buffer("volume.reservoirs.a", desc);
  // Without history the radiance buffer stands in for the history binding (never read: the flag
  // is off; it is written before this pass, so the graph sees an ordinary read).
  scratch = initial_.add(graph, inputs, push,
                         {{"reservoirs", scratch, ShaderPassBuffer::Write},
                          {"reservoirs_history", history.valid() ? history : hdr,
                           ShaderPassBuffer::Read}},
                         dispatch)[0];
  const auto written = spatial_.add(graph, inputs, push,
                                    {{"reservoirs_in", scratch, ShaderPassBuffer::Read},
                                     {"reservoirs", final_reservoirs, ShaderPassBuffer::Write},
                                     {"radiance", hdr, ShaderPassBuffer::ReadWrite}},
                                    dispatch);
  return written[1];
}

}  // namespace lantern::lighting
