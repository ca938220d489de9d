// Raster path for the G-buffer pass: a graphics pipeline with dynamic rendering, colour + depth
// attachments, a vertex buffer and push constants; the result is read back and checked.
#include <gtest/gtest.h>

#include <array>
#include <cstring>

#include "gpu_test_support.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/graphics_pipeline.h"
#include "runtime/gpu/image.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/gpu/transfer.h"

namespace lantern::runtime {
namespace {

using GpuRaster = test::GpuTest;

TEST_F(GpuRaster, TriangleWithColorAndDepth) {
  ASSERT_TRUE(device.caps().dynamic_rendering);
  constexpr std::uint32_t kSize = 32;
  ShaderLibrary shaders;
  GraphicsPipelineDesc desc{.name = "test.triangle",
                            .color_formats = {VK_FORMAT_R8G8B8A8_UNORM},
                            .depth_format = VK_FORMAT_D32_SFLOAT,
                            .vertex_stride = 8,
                            .vertex_attributes = {{0, 0, VK_FORMAT_R32G32_SFLOAT, 0}},
                            .cull_mode = VK_CULL_MODE_NONE};
  const GraphicsPipeline pipeline(device, shaders.load("tests/runtime_triangle.vert"),
                                  shaders.load("tests/runtime_triangle.frag"), desc);
  EXPECT_EQ(pipeline.push_constant_bytes(), 16u);

  const std::array<float, 6> triangle = {-0.5f, -0.5f, 0.5f, -0.5f, 0.0f, 0.5f};
  Buffer vertices(device, {.size = sizeof(triangle),
                           .usage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                           .name = "test.vertices"});
  upload_buffer<float>(device, vertices, triangle);
  Image color(device, {.width = kSize,
                       .height = kSize,
                       .format = VK_FORMAT_R8G8B8A8_UNORM,
                       .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                       .name = "test.color"});
  Image depth(device, {.width = kSize,
                       .height = kSize,
                       .format = VK_FORMAT_D32_SFLOAT,
                       .usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                       .name = "test.depth"});

  device.submit_and_wait([&](VkCommandBuffer cmd) {
    transition_image(device, cmd, color, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    transition_image(device, cmd, depth, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
    const ColorTarget target{.view = color.view(),
                             .clear = VkClearColorValue{{0.0f, 0.0f, 1.0f, 1.0f}}};
    const DepthTarget depth_target{.view = depth.view(), .clear = 1.0f};
    begin_rendering(device, cmd, color.extent(), std::span(&target, 1), &depth_target);
    pipeline.bind(cmd);
    const VkDeviceSize offset = 0;
    const VkBuffer vertex_buffer = vertices.handle();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
    const std::array<float, 4> red = {1.0f, 0.0f, 0.0f, 1.0f};
    pipeline.push_constants(cmd, red);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    end_rendering(device, cmd);
  });

  const auto pixels = read_image(device, color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  auto pixel = [&](std::uint32_t x, std::uint32_t y) {
    std::array<std::uint8_t, 4> p{};
    std::memcpy(p.data(), pixels.data() + (y * kSize + x) * 4, 4);
    return p;
  };
  EXPECT_EQ(pixel(16, 16), (std::array<std::uint8_t, 4>{255, 0, 0, 255}))
      << "centre is inside the triangle";
  EXPECT_EQ(pixel(1, 1), (std::array<std::uint8_t, 4>{0, 0, 255, 255}))
      << "corner keeps the clear colour";

  const auto depths = read_image(device, depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
  float centre_depth = 0.0f, corner_depth = 0.0f;
  std::memcpy(&centre_depth, depths.data() + (16 * kSize + 16) * 4, 4);
  std::memcpy(&corner_depth, depths.data() + (1 * kSize + 1) * 4, 4);
  EXPECT_FLOAT_EQ(centre_depth, 0.5f);
  EXPECT_FLOAT_EQ(corner_depth, 1.0f);
}

}  // namespace
}  // namespace lantern::runtime
