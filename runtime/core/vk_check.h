// VK_CHECK(call): on failure throws lantern::RuntimeError naming the call, the VkResult and the
// source location, e.g. "vkCreateDevice(...) failed: VK_ERROR_INITIALIZATION_FAILED at
// device.cpp:120".
#pragma once

#include <vulkan/vulkan.h>

#include <string_view>

namespace lantern::runtime {

std::string_view vk_result_name(VkResult result);
[[noreturn]] void vk_fail(VkResult result, const char* call, const char* file, int line);

}  // namespace lantern::runtime

#define VK_CHECK(call)                                                            \
  do {                                                                            \
    const VkResult lantern_vk_result_ = (call);                                   \
    if (lantern_vk_result_ < 0)                                                   \
      ::lantern::runtime::vk_fail(lantern_vk_result_, #call, __FILE__, __LINE__); \
  } while (0)
