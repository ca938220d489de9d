// Resources on the GPU: image upload/readback, a pipeline using every binding kind (bound by
// name), and the memory sub-allocator's block accounting.
#include <gtest/gtest.h>

#include <cstring>
#include <glm/glm.hpp>

#include "gpu_test_support.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/image.h"
#include "runtime/gpu/memory_allocator.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/gpu/transfer.h"

namespace lantern::runtime {
namespace {

using GpuResources = test::GpuTest;

TEST_F(GpuResources, ImageUploadReadbackRoundTrip) {
  Image image(device, {.width = 17,
                       .height = 9,
                       .format = VK_FORMAT_R32G32B32A32_SFLOAT,
                       .usage = VK_IMAGE_USAGE_STORAGE_BIT,
                       .name = "test.image"});
  std::vector<float> texels(17 * 9 * 4);
  for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<float>(i) * 0.25f;
  upload_image(device, image, std::as_bytes(std::span(texels)), VK_IMAGE_LAYOUT_GENERAL);
  const auto bytes = read_image(device, image, VK_IMAGE_LAYOUT_GENERAL);
  ASSERT_EQ(bytes.size(), texels.size() * 4);
  EXPECT_EQ(std::memcmp(bytes.data(), texels.data(), bytes.size()), 0);
}

// The discrete-GPU path: device-local memory without host pointers, uploads through staging.
TEST(GpuStaging, BufferRoundTripThroughStaging) {
  DeviceOptions options = test::test_device_options();
  options.force_staging = true;
  Device device(options);
  std::vector<std::uint32_t> data(10'000);
  for (std::uint32_t i = 0; i < data.size(); ++i) data[i] = i * 2654435761u;
  Buffer buffer(device, {.size = data.size() * 4,
                         .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         .name = "test.staged"});
  EXPECT_EQ(buffer.mapped(), nullptr);
  upload_buffer<std::uint32_t>(device, buffer, data, 0);
  EXPECT_EQ(read_buffer<std::uint32_t>(device, buffer), data);
  const std::vector<std::uint32_t> patch = {1, 2, 3};
  upload_buffer<std::uint32_t>(device, buffer, patch, 8);
  const auto patched = read_buffer<std::uint32_t>(device, buffer);
  EXPECT_EQ(patched[1], data[1]);
  EXPECT_EQ(patched[2], 1u);
  EXPECT_EQ(patched[4], 3u);
  EXPECT_EQ(patched[5], data[5]);
  EXPECT_TRUE(device.validation_enabled());
  EXPECT_EQ(device.validation_errors(), 0u);
}

TEST_F(GpuResources, EveryBindingKindBoundByName) {
  struct Push {
    glm::mat4 transform;
    glm::uvec4 size;
  };
  constexpr std::uint32_t kW = 16, kH = 8;
  ShaderLibrary shaders;
  ComputePipelineDesc desc{.name = "test.reflect"};
  desc.constants.set("kScale", 3.0f);
  const ComputePipeline pipeline(device, shaders.load("tests/runtime_reflect.comp"), desc);

  Buffer frame(device, {.size = 16,
                        .usage = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                        .memory = MemoryUsage::Upload,
                        .name = "frame"});
  Buffer source(
      device,
      {.size = kW * kH * 16, .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, .name = "source"});
  Buffer reservoirs(
      device,
      {.size = kW * kH * 16, .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, .name = "reservoirs"});
  Image radiance(device, {.width = kW,
                          .height = kH,
                          .format = VK_FORMAT_R32G32B32A32_SFLOAT,
                          .usage = VK_IMAGE_USAGE_STORAGE_BIT,
                          .name = "radiance"});
  Image history(device, {.width = 1,
                         .height = 1,
                         .format = VK_FORMAT_R32G32B32A32_SFLOAT,
                         .usage = VK_IMAGE_USAGE_SAMPLED_BIT,
                         .name = "history"});
  const glm::vec4 tint(1.0f, 2.0f, 0.5f, 1.0f);
  const glm::vec4 history_value(0.25f, 0.0f, 1.0f, 0.0f);
  upload_buffer<glm::vec4>(device, frame, std::span(&tint, 1));
  std::vector<glm::vec4> texels(kW * kH);
  for (std::uint32_t i = 0; i < texels.size(); ++i)
    texels[i] = glm::vec4(float(i), 1.0f, -1.0f, 2.0f);
  upload_buffer<glm::vec4>(device, source, texels);
  upload_image(device, history, std::as_bytes(std::span(&history_value, 1)),
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);

  VkSamplerCreateInfo sampler_info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  VkSampler sampler = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateSampler(device.handle(), &sampler_info, nullptr, &sampler), VK_SUCCESS);
  device.submit_and_wait([&](VkCommandBuffer cmd) {
    transition_image(device, cmd, radiance, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    // Deliberately not in binding order: names decide.
    pipeline.bind(cmd, Bindings(pipeline)
                           .sampled_image("history", history, sampler)
                           .storage_image("radiance", radiance)
                           .buffer("Reservoirs", reservoirs)
                           .buffer("source", source)
                           .buffer("frame", frame));
    pipeline.push_constants(cmd, Push{glm::mat4(1.0f), glm::uvec4(kW, kH, 0, 0)});
    pipeline.dispatch_threads(cmd, kW, kH);
  });
  vkDestroySampler(device.handle(), sampler, nullptr);

  const auto pixels = read_image(device, radiance, VK_IMAGE_LAYOUT_GENERAL);
  const auto ids = read_buffer<glm::uvec4>(device, reservoirs);
  for (std::uint32_t i = 0; i < kW * kH; ++i) {
    glm::vec4 got;
    std::memcpy(&got, pixels.data() + i * 16, 16);
    const glm::vec4 want = (texels[i] * tint + history_value) * 3.0f;
    ASSERT_EQ(got, want) << "pixel " << i;
    ASSERT_EQ(ids[i], glm::uvec4(i)) << "reservoir " << i;
  }
}

TEST_F(GpuResources, SubAllocatorSharesBlocksAndReleasesMemory) {
  auto total = [&](auto member) {
    VkDeviceSize sum = 0;
    for (const HeapStats& h : device.memory().stats()) sum += h.*member;
    return sum;
  };
  auto blocks = [&] {
    std::uint32_t n = 0;
    for (const HeapStats& h : device.memory().stats()) n += h.blocks;
    return n;
  };
  const VkDeviceSize used_before = total(&HeapStats::used);
  const std::uint32_t blocks_before = blocks();
  {
    std::vector<Buffer> small;
    for (int i = 0; i < 32; ++i)
      small.emplace_back(device, BufferDesc{.size = 256 << 10,
                                            .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                            .name = "test.small" + std::to_string(i)});
    EXPECT_GE(total(&HeapStats::used), used_before + 32 * (256 << 10));
    EXPECT_LE(blocks(), blocks_before + 1) << "32 x 256 KiB must share one 64 MiB block";
    const VkDeviceSize big_size = device.memory().block_size();  // > half a block: dedicated
    Buffer big(device,
               {.size = big_size, .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, .name = "test.big"});
    EXPECT_GE(total(&HeapStats::reserved), total(&HeapStats::used));
    EXPECT_NE(describe(device.memory().stats()).find("MiB used by"), std::string::npos);
    EXPECT_GE(total(&HeapStats::used), used_before + 32 * (256 << 10) + big_size);
  }
  EXPECT_EQ(total(&HeapStats::used), used_before) << "all bytes returned";
  EXPECT_LE(blocks(), blocks_before + 1)
      << "dedicated memory freed; at most one cached empty block";
}

}  // namespace
}  // namespace lantern::runtime
