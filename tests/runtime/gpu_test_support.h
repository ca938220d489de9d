// Shared fixture for GPU tests: a validated device, and a check at the end of every test that
// validation really ran and reported no error.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>

#include "runtime/core/device.h"

namespace lantern::runtime::test {

inline DeviceOptions test_device_options() {
  DeviceOptions options;
  options.validation = true;
  options.cache_dir = std::filesystem::temp_directory_path() / "lantern_test_pipeline_cache";
  return options;
}

class GpuTest : public ::testing::Test {
 protected:
  GpuTest() : GpuTest(test_device_options()) {}
  explicit GpuTest(const DeviceOptions& options) : device(options) {}
  void TearDown() override {
    EXPECT_TRUE(device.validation_enabled())
        << "validation layer unavailable: the test cannot vouch for API use";
    EXPECT_EQ(device.validation_errors(), 0u);
  }
  Device device;
};

}  // namespace lantern::runtime::test
