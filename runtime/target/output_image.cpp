// Output image creation and its per-frame import.
#include "runtime/target/output_image.h"

#include <utility>

namespace lantern::runtime {
namespace {

Image make_image(Device& device, VkExtent2D extent, const std::string& name) {
  return Image(device, {.width = extent.width,
                        .height = extent.height,
                        .format = OutputImage::kFormat,
                        .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                        .name = name});
}

}  // namespace

OutputImage::OutputImage(Device& device, VkExtent2D extent, std::string name)
    : device_(device), name_(std::move(name)), image_(make_image(device_, extent, name_)) {}

graph::ImageHandle OutputImage::import(graph::RenderGraph& graph,
                                       const graph::AccessState& delivered) {
  graph::ImportInfo info;
  info.initial = state_;
  info.final = delivered;
  pending_ = delivered;
  graph::ImageDesc desc;
  desc.extent = {image_.extent().width, image_.extent().height, 1};
  desc.format = kFormat;
  return graph.import_image(name_, image_.handle(), image_.view(), desc, info);
}

void OutputImage::resize(VkExtent2D extent) {
  image_ = make_image(device_, extent, name_);
  state_ = pending_ = {};
}

}  // namespace lantern::runtime
