// GPU smoke test: a compute shader writes a pattern (spec-constant workgroup size and multiplier,
// push-constant count/offset); every element is checked on the CPU. Timestamps and warm-up too.
#include <gtest/gtest.h>

#include <filesystem>
#include <numeric>
#include <string>

#include "engine/core/error.h"
#include "gpu_test_support.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/glsl_compiler.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/gpu/transfer.h"

namespace lantern::runtime {
namespace {

struct FillPush {
  std::uint32_t count;
  std::uint32_t offset;
};

class GpuSmoke : public test::GpuTest {
 protected:
  ComputePipeline make_fill(std::uint32_t group_size, std::uint32_t multiplier) {
    ComputePipelineDesc desc{.name = "test.fill"};
    desc.constants.set_id(0, group_size).set("kMultiplier", multiplier);
    return ComputePipeline(device, shaders.load("tests/runtime_fill.comp"), desc);
  }
  ShaderLibrary shaders;
};

TEST_F(GpuSmoke, ComputePatternCheckedOnCpu) {
  constexpr std::uint32_t kCount = 100'003;  // not a multiple of the workgroup size
  const ComputePipeline fill = make_fill(64, 7);
  EXPECT_EQ(fill.local_size()[0], 64u);
  Buffer out(device, {.size = kCount * 4 + 64,
                      .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                      .memory = MemoryUsage::Readback,
                      .name = "test.fill.out"});
  std::vector<std::uint32_t> sentinel(out.size() / 4, 0xdeadbeefu);
  upload_buffer<std::uint32_t>(device, out, sentinel);

  device.submit_and_wait([&](VkCommandBuffer cmd) {
    CommandLabel label(device, cmd, "test.fill");
    fill.bind(cmd, Bindings(fill).buffer("result", out));
    fill.push_constants(cmd, FillPush{kCount, 11});
    fill.dispatch_threads(cmd, kCount);
  });

  const auto values = read_buffer<std::uint32_t>(device, out);
  ASSERT_EQ(values.size(), kCount + 16u);
  std::uint32_t wrong = 0;
  for (std::uint32_t i = 0; i < kCount; ++i) wrong += values[i] != i * 7u + 11u;
  EXPECT_EQ(wrong, 0u) << "first values: " << values[0] << " " << values[1] << " " << values[2];
  for (std::uint32_t i = kCount; i < values.size(); ++i)
    EXPECT_EQ(values[i], 0xdeadbeefu) << "wrote past count at " << i;
}

// The hot-reload path: GLSL compiled at run time by the glslang library, then dispatched.
TEST_F(GpuSmoke, RuntimeCompiledShaderRuns) {
  const auto source = std::filesystem::path(LANTERN_SOURCE_DIR) / "shaders/tests/runtime_fill.comp";
  GlslResult compiled = compile_glsl(source);
  ASSERT_TRUE(compiled.ok()) << compiled.log;
  ComputePipelineDesc desc{.name = "test.fill.hot"};
  desc.constants.set_id(0, 32).set("kMultiplier", 5u);
  const ComputePipeline fill(device,
                             make_shader_code("hot:runtime_fill", std::move(compiled.spirv)), desc);
  constexpr std::uint32_t kCount = 1000;
  Buffer out(device, {.size = kCount * 4,
                      .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                      .memory = MemoryUsage::Readback,
                      .name = "test.hot.out"});
  device.submit_and_wait([&](VkCommandBuffer cmd) {
    fill.bind(cmd, Bindings(fill).buffer("result", out));
    fill.push_constants(cmd, FillPush{kCount, 2});
    fill.dispatch_threads(cmd, kCount);
  });
  const auto values = read_buffer<std::uint32_t>(device, out);
  for (std::uint32_t i = 0; i < kCount; ++i) ASSERT_EQ(values[i], i * 5u + 2u) << i;
}

TEST_F(GpuSmoke, DeviceLocalBufferRoundTrip) {
  std::vector<std::uint32_t> data(4096);
  std::iota(data.begin(), data.end(), 5u);
  Buffer buffer(device, {.size = data.size() * 4,
                         .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         .name = "test.roundtrip"});
  upload_buffer<std::uint32_t>(device, buffer, data);
  EXPECT_EQ(read_buffer<std::uint32_t>(device, buffer), data);
  EXPECT_THROW(upload_buffer<std::uint32_t>(device, buffer, data, 4), RuntimeError)
      << "overflow must be rejected";
}

TEST_F(GpuSmoke, TimestampsMeasureADispatch) {
  constexpr std::uint32_t kCount = 1 << 22;
  const ComputePipeline fill = make_fill(256, 3);
  fill.warm_up();
  Buffer out(
      device,
      {.size = kCount * 4, .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, .name = "test.timed"});
  GpuTimer timer(device, 8);
  device.submit_and_wait([&](VkCommandBuffer cmd) {
    timer.reset(cmd);
    auto frame = timer.scope(cmd, "test.frame");
    {
      auto pass = timer.scope(cmd, "test.fill");
      fill.bind(cmd, Bindings(fill).buffer("result", out));
      fill.push_constants(cmd, FillPush{kCount, 0});
      fill.dispatch_threads(cmd, kCount);
    }
  });
  const auto results = timer.resolve();
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].name, "test.frame");
  EXPECT_EQ(results[0].depth, 0u);
  EXPECT_EQ(results[1].name, "test.fill");
  EXPECT_EQ(results[1].depth, 1u);
  EXPECT_GT(results[1].ms, 0.0);
  EXPECT_LT(results[1].ms, 10'000.0);
  EXPECT_GE(results[0].ms, results[1].ms) << "the enclosing scope cannot be shorter";
  std::printf("test.fill: %.3f ms for %u invocations\n", results[1].ms, kCount);
}

TEST_F(GpuSmoke, BindingByNameRejectsMistakes) {
  const ComputePipeline fill = make_fill(64, 1);
  Buffer out(device,
             {.size = 256, .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, .name = "test.out"});
  try {
    Bindings(fill).buffer("results", out);
    FAIL() << "misspelt binding accepted";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("result (storage buffer)"), std::string::npos)
        << "the error should list the shader's bindings: " << e.what();
  }
  Bindings empty(fill);
  EXPECT_THROW(empty.writes(), RuntimeError) << "unbound 'result' must be reported";
  EXPECT_THROW(fill.push_constants(VkCommandBuffer{VK_NULL_HANDLE}, std::uint32_t{1}), RuntimeError)
      << "push constant size mismatch";
  ComputePipelineDesc bad{.name = "test.bad"};
  bad.constants.set("kNoSuchConstant", 1u);
  EXPECT_THROW(ComputePipeline(device, shaders.load("tests/runtime_fill.comp"), bad), RuntimeError);
}

}  // namespace
}  // namespace lantern::runtime
