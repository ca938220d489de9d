// target.present: the render-graph pass that copies the target's output image to a swapchain
// image (nearest scaling, clamp, sRGB encode; shaders/target/target_present.comp).
// Reads: output (storage, compute). Writes: the imported swapchain image (storage, compute).
// Dispatch: 8x8 groups over the swapchain extent.
#pragma once

#include <vulkan/vulkan.h>

#include "runtime/gpu/compute_pipeline.h"
#include "runtime/graph/render_graph.h"

namespace lantern::runtime {

class Device;
class ShaderLibrary;

class PresentPass {
 public:
  // Throws lantern::RuntimeError when the device cannot write storage images without a format
  // qualifier (the swapchain's format is chosen at run time).
  PresentPass(Device& device, ShaderLibrary& shaders);

  // The state the pass leaves the output image in (its read), for OutputImage::import.
  static graph::AccessState source_state();
  // The stage the swapchain image is first written at (wait the acquire semaphore there).
  static constexpr VkPipelineStageFlags2 kDestinationStage = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

  void add(graph::RenderGraph& graph, graph::ImageHandle source, VkExtent2D source_extent,
           graph::ImageHandle destination, VkExtent2D destination_extent) const;
  void warm_up() const { pipeline_.warm_up(); }

 private:
  ComputePipeline pipeline_;
};

}  // namespace lantern::runtime
