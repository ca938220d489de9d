// target.present: declaration and recording.
#include "runtime/target/present_pass.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "runtime/core/device.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::runtime {
namespace {

struct PresentPush {
  std::uint32_t source_size[2];
  std::uint32_t destination_size[2];
};

ComputePipeline make_pipeline(Device& device, ShaderLibrary& shaders) {
  if (!device.caps().storage_image_without_format)
    throw RuntimeError(
        fmt::format("device '{}' cannot write storage images without a format qualifier "
                    "(shaderStorageImageWriteWithoutFormat): target.present needs it",
                    device.info().name));
  return ComputePipeline(device, shaders.load("target/target_present.comp"),
                         {.name = "target.present"});
}

}  // namespace

PresentPass::PresentPass(Device& device, ShaderLibrary& shaders)
    : pipeline_(make_pipeline(device, shaders)) {}

graph::AccessState PresentPass::source_state() {
  return graph::access_state(graph::Access::StorageRead, graph::PassKind::Compute, true);
}

void PresentPass::add(graph::RenderGraph& graph, graph::ImageHandle source,
                      VkExtent2D source_extent, graph::ImageHandle destination,
                      VkExtent2D destination_extent) const {
  struct Data {
    graph::ImageHandle source;
    graph::ImageHandle destination;
  };
  graph.add_pass<Data>(
      "target.present", graph::PassKind::Compute,
      [&](graph::PassBuilder& b, Data& d) {
        b.read(source, graph::Access::StorageRead);
        d.source = source;
        d.destination = b.write(destination, graph::Access::StorageWrite);
        b.side_effect();
      },
      [this, source_extent, destination_extent](graph::PassContext& ctx, const Data& d) {
        pipeline_.bind(
            ctx.cmd(),
            Bindings(pipeline_)
                .image_view("source", ctx.view(d.source), VK_IMAGE_LAYOUT_GENERAL)
                .image_view("destination", ctx.view(d.destination), VK_IMAGE_LAYOUT_GENERAL));
        pipeline_.push_constants(
            ctx.cmd(), PresentPush{{source_extent.width, source_extent.height},
                                   {destination_extent.width, destination_extent.height}});
        pipeline_.dispatch_threads(ctx.cmd(), destination_extent.width, destination_extent.height);
      });
}

}  // namespace lantern::runtime
