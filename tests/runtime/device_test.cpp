// Device enumeration, selection errors, capabilities and debug names on a real device.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "engine/core/error.h"
#include "gpu_test_support.h"
#include "runtime/gpu/buffer.h"

namespace lantern::runtime {
namespace {

TEST(Device, EnumerateListsUsableDevices) {
  const auto devices = Device::enumerate();
  ASSERT_FALSE(devices.empty());
  for (std::uint32_t i = 0; i < devices.size(); ++i) {
    EXPECT_EQ(devices[i].index, i);
    EXPECT_FALSE(devices[i].name.empty());
    EXPECT_FALSE(devices[i].api_version.empty());
    EXPECT_GT(devices[i].device_local_bytes, 0u);
  }
}

TEST(Device, BadSelectorsAreInputErrorsNamingDevices) {
  const auto devices = Device::enumerate();
  DeviceOptions options = test::test_device_options();
  options.selector = std::to_string(devices.size());
  try {
    Device device(options);
    FAIL() << "index out of range accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(devices[0].name), std::string::npos) << e.what();
  }
  const bool has_gpu = std::any_of(devices.begin(), devices.end(), [](const DeviceInfo& d) {
    return d.type == "discrete" || d.type == "integrated";
  });
  options.selector = "gpu";
  if (has_gpu) {
    EXPECT_NO_THROW(Device device(options));
  } else {
    EXPECT_THROW(Device device(options), InputError);
  }
}

// The counter must really see errors, or "zero validation errors" in every other test means
// nothing.
TEST(Device, ValidationCountsAnInvalidCall) {
  Device device(test::test_device_options());
  ASSERT_TRUE(device.validation_enabled());
  ASSERT_EQ(device.validation_errors(), 0u);
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 0;  // VUID-VkBufferCreateInfo-size-00912: size must be greater than 0
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  std::fprintf(stderr, "(the validation error below is expected)\n");
  VkBuffer buffer = VK_NULL_HANDLE;
  const VkResult result = vkCreateBuffer(device.handle(), &info, nullptr, &buffer);
  if (result == VK_SUCCESS) vkDestroyBuffer(device.handle(), buffer, nullptr);
  EXPECT_GE(device.validation_errors(), 1u);
}

using DeviceCapsTest = test::GpuTest;

TEST_F(DeviceCapsTest, RequiredFeaturesAndSaneLimits) {
  EXPECT_TRUE(device.caps().synchronization2);
  EXPECT_GE(device.caps().api_version, static_cast<std::uint32_t>(VK_API_VERSION_1_2));
  EXPECT_GT(device.caps().timestamp_valid_bits, 0u);
  EXPECT_GT(device.caps().timestamp_period_ns, 0.0f);
  EXPECT_GE(device.caps().max_push_descriptors, 8u);
  EXPECT_NE(device.fn().cmd_push_descriptor_set, nullptr);
  EXPECT_NE(device.fn().cmd_pipeline_barrier2, nullptr);
  EXPECT_EQ(device.caps().ray_query, device.info().ray_query)
      << "enabled whenever the device offers it";
  if (device.caps().ray_query) {
    EXPECT_TRUE(device.caps().buffer_device_address);
  }
}

TEST_F(DeviceCapsTest, DebugNamesAndLabelsAreAccepted) {
  EXPECT_TRUE(device.caps().debug_utils);
  Buffer buffer(device,
                {.size = 64, .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, .name = "test.named"});
  device.set_name(buffer.handle(), "test.renamed");
  device.submit_and_wait([&](VkCommandBuffer cmd) {
    CommandLabel outer(device, cmd, "test.outer");
    CommandLabel inner(device, cmd, "test.inner");
  });
}

// The soak test's "no growth in live Vulkan objects" rests on this counter seeing objects.
TEST(Device, CountingAllocatorSeesObjectsComeAndGo) {
  DeviceOptions options = test::test_device_options();
  EXPECT_THROW(Device(options).live_driver_allocations(), RuntimeError);
  options.count_driver_allocations = true;
  Device device(options);
  EXPECT_GT(device.live_driver_allocations().total, 0) << "the device is allocated through it";
  auto make_buffer = [&](const char* name) {
    return Buffer(device, {.size = 256, .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, .name = name});
  };
  make_buffer("test.first");  // the memory allocator keeps the VkDeviceMemory block it opens
  const AllocationCounts before = device.live_driver_allocations();
  {
    const Buffer a = make_buffer("test.a");
    const Buffer b = make_buffer("test.b");
    const AllocationCounts during = device.live_driver_allocations();
    EXPECT_GE(during.object, before.object + 2) << "one or more per VkBuffer";
    EXPECT_GT(during.bytes, before.bytes);
  }
  const AllocationCounts after = device.live_driver_allocations();
  EXPECT_EQ(after.object, before.object) << "destroyed buffers are no longer live";
  EXPECT_EQ(after.bytes, before.bytes);
  EXPECT_EQ(device.validation_errors(), 0u);
}

}  // namespace
}  // namespace lantern::runtime
