// frame.output: the HDR buffer into a target image, linear or tonemapped
// (shaders/frame/frame_output.comp). Reads: hdr (StorageRead). Writes: target (StorageWrite).
// History: none. Dispatch: one thread per pixel, 8x8 groups.
#pragma once

#include <cstdint>

#include "runtime/gpu/compute_pipeline.h"
#include "runtime/graph/render_graph.h"

namespace lantern::lighting {

// Returns the new version of `target`. `pipeline` is shaders/frame/frame_output.comp; exposure 0
// copies linear radiance, > 0 applies exposure and the filmic curve.
[[nodiscard]] runtime::graph::ImageHandle add_frame_output_pass(
    runtime::graph::RenderGraph& graph, const runtime::ComputePipeline& pipeline,
    runtime::graph::BufferHandle hdr, runtime::graph::ImageHandle target, std::uint32_t width,
    std::uint32_t height, float exposure);

}  // namespace lantern::lighting
