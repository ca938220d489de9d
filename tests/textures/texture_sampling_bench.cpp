// Benchmark, not a test: the cost of one bilinear texture sample on this device, hardware
// sampler (what a bindless array of sampled images would use) vs the project's software path
// (lib/textures.glsl on a storage buffer, rgba8 data and rgba16f colour texels). 640x360 threads x
// 16 taps from a 512x512 texture; median GPU ms of 9 dispatches each, printed per mode.
// Usage: texture_sampling_bench
#include <algorithm>
#include <cstdio>
#include <glm/glm.hpp>
#include <vector>

#include "lighting/textures/texture_set.h"
#include "runtime/core/device.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/gpu/image.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/gpu/transfer.h"
#include "tests/textures/textured_assets.h"

using namespace lantern;

int main() {
  runtime::Device device(runtime::DeviceOptions{});
  runtime::ShaderLibrary shaders;
  constexpr std::uint32_t kSize = 512;
  const std::vector<std::uint8_t> rgba8 =
      test::make_rgba8(kSize, kSize, [](std::uint32_t x, std::uint32_t y) {
        return glm::vec4((x ^ y) % 256 / 255.0f, x % 256 / 255.0f, y % 256 / 255.0f, 1.0f);
      });
  // Software paths: the texture set's own texels and records (mips included, lod 0 sampled): the
  // image as a colour texture (sRGB decoded at load, rgba16f) and as a data texture (rgba8).
  Level level;
  Material m;
  m.base_color_texture.image = test::add_png(level, kSize, kSize, rgba8);
  m.metallic_roughness_texture.image = m.base_color_texture.image;
  level.materials.push_back(m);
  const lighting::TextureSet set = lighting::TextureSet::build(level);
  auto storage = [&](auto values, const char* name) {
    runtime::Buffer b(device, {.size = values.size_bytes(),
                               .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               .memory = runtime::MemoryUsage::DeviceLocal,
                               .name = name});
    runtime::upload_buffer(device, b, values);
    return b;
  };
  runtime::Buffer texels = storage(std::span(set.texels()), "bench.texels");
  // Record 0 first: the shader samples record 0.
  const std::vector<gpu::GpuTexture> half_record = {set.records()[set.material_textures(0).x]};
  const std::vector<gpu::GpuTexture> rgba8_record = {set.records()[set.material_textures(0).y]};
  runtime::Buffer half_records = storage(std::span(half_record), "bench.half_record");
  runtime::Buffer rgba8_records = storage(std::span(rgba8_record), "bench.rgba8_record");
  runtime::Buffer out(device, {.size = 640 * 360 * 16,
                               .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               .memory = runtime::MemoryUsage::DeviceLocal,
                               .name = "bench.out"});
  // Hardware path: the same level-0 texels in an sRGB image with a linear/repeat sampler.
  runtime::Image image(device, {.width = kSize,
                                .height = kSize,
                                .format = VK_FORMAT_R8G8B8A8_SRGB,
                                .usage = VK_IMAGE_USAGE_SAMPLED_BIT,
                                .name = "bench.image"});
  runtime::upload_image(device, image, std::as_bytes(std::span(rgba8)),
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_LINEAR;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  VkSampler sampler = VK_NULL_HANDLE;
  vkCreateSampler(device.handle(), &si, nullptr, &sampler);
  runtime::GpuTimer timer(device, 4);
  for (const int mode : {0, 1, 2}) {  // software rgba8, software rgba16f, hardware
    const bool hardware = mode == 2;
    runtime::ComputePipeline pipeline(
        device, shaders.load("tests/texture_sampling_bench.comp"),
        runtime::ComputePipelineDesc{
            .name = "bench.texture_sampling",
            .constants = runtime::SpecConstants().set("kHardware", hardware)});
    std::vector<double> ms;
    for (int run = 0; run < 10; ++run) {
      device.submit_and_wait([&](VkCommandBuffer cmd) {
        timer.reset(cmd);
        timer.begin(cmd, "sample");
        pipeline.bind(cmd, runtime::Bindings(pipeline)
                               .sampled_image("bench_image", image, sampler)
                               .buffer("scene_texels", texels)
                               .buffer("scene_textures", mode == 0 ? rgba8_records : half_records)
                               .buffer("bench_out", out));
        pipeline.dispatch_threads(cmd, 640, 360);
        timer.end(cmd);
      });
      if (run > 0) ms.push_back(timer.resolve().at(0).ms);  // run 0 pays the JIT
    }
    std::sort(ms.begin(), ms.end());
    const double median = ms[ms.size() / 2];
    const char* names[] = {"software rgba8", "software rgba16f", "hardware sampler rgba8 srgb"};
    std::printf("%-28s %7.2f ms  (%.1f ns per bilinear sample)\n", names[mode], median,
                median * 1e6 / (640.0 * 360.0 * 16.0));
  }
  vkDestroySampler(device.handle(), sampler, nullptr);
  return 0;
}
