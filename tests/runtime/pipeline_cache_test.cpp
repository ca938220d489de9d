// The pipeline cache is written to disk when a device goes away and accepted by the next one.
#include "runtime/gpu/pipeline_cache.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "gpu_test_support.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"
#include "tests/runtime/scratch_dir.h"

namespace lantern::runtime {
namespace {

TEST(PipelineCache, WrittenOnShutdownAndReloaded) {
  const auto dir = lantern::test::process_scratch_dir() / "pipeline_cache";
  std::filesystem::remove_all(dir);
  DeviceOptions options = test::test_device_options();
  options.cache_dir = dir;
  ShaderLibrary shaders;
  std::filesystem::path file;
  {
    Device device(options);
    EXPECT_EQ(device.pipeline_cache_store().loaded_bytes(), 0u)
        << "fresh directory: nothing to load";
    ComputePipelineDesc desc{.name = "test.cached"};
    desc.constants.set_id(0, 32);
    const ComputePipeline pipeline(device, shaders.load("tests/runtime_fill.comp"), desc);
    file = device.pipeline_cache_store().file();
    EXPECT_EQ(file.parent_path(), dir);
    EXPECT_TRUE(device.validation_enabled());
    EXPECT_EQ(device.validation_errors(), 0u);
  }
  ASSERT_TRUE(std::filesystem::exists(file)) << file;
  const auto size = std::filesystem::file_size(file);
  // At least the VkPipelineCacheHeaderVersionOne header (lavapipe stores nothing else: its JIT
  // cache is Mesa's own on-disk shader cache).
  EXPECT_GE(size, sizeof(VkPipelineCacheHeaderVersionOne));
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path(), file) << "no temp files left behind";
  {
    Device device(options);
    EXPECT_EQ(device.pipeline_cache_store().loaded_bytes(), size);
    EXPECT_EQ(device.validation_errors(), 0u);
  }
  {  // A corrupted file is ignored, not fatal.
    std::ofstream(file, std::ios::binary | std::ios::trunc)
        << "garbage that is not a pipeline cache header......";
    Device device(options);
    EXPECT_EQ(device.pipeline_cache_store().loaded_bytes(), 0u);
    EXPECT_EQ(device.validation_errors(), 0u);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace lantern::runtime
