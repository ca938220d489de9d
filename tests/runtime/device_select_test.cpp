// The --device selection rule over fabricated device lists (no Vulkan needed).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/core/error.h"
#include "runtime/core/device_info.h"

namespace lantern::runtime {
namespace {

DeviceInfo make(std::uint32_t index, std::string name, std::string type) {
  DeviceInfo d;
  d.index = index;
  d.name = std::move(name);
  d.type = std::move(type);
  return d;
}

TEST(DeviceSelect, AutoPrefersDiscreteThenIntegratedThenCpu) {
  const std::vector<DeviceInfo> all = {make(0, "llvmpipe", "cpu"), make(1, "igpu", "integrated"),
                                       make(2, "dgpu", "discrete")};
  EXPECT_EQ(select_device(all, "auto"), 2u);
  const std::vector<DeviceInfo> no_discrete = {make(0, "llvmpipe", "cpu"),
                                               make(1, "igpu", "integrated")};
  EXPECT_EQ(select_device(no_discrete, "auto"), 1u);
  const std::vector<DeviceInfo> cpu_only = {make(0, "llvmpipe", "cpu")};
  EXPECT_EQ(select_device(cpu_only, "auto"), 0u);
}

TEST(DeviceSelect, CpuGpuAndIndex) {
  const std::vector<DeviceInfo> all = {make(0, "dgpu", "discrete"), make(1, "llvmpipe", "cpu")};
  EXPECT_EQ(select_device(all, "cpu"), 1u);
  EXPECT_EQ(select_device(all, "gpu"), 0u);
  EXPECT_EQ(select_device(all, "1"), 1u);
}

TEST(DeviceSelect, BadSelectorsNameTheAvailableDevices) {
  const std::vector<DeviceInfo> cpu_only = {make(0, "llvmpipe (LLVM 15)", "cpu")};
  for (const char* selector : {"gpu", "3", "-1", "fast", ""}) {
    try {
      select_device(cpu_only, selector);
      FAIL() << "selector '" << selector << "' should be rejected";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("llvmpipe (LLVM 15)"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(select_device({}, "auto"), InputError);
}

}  // namespace
}  // namespace lantern::runtime
