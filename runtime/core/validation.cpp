// Validation policy and the debug-utils message counter.
#include "runtime/core/validation.h"

#include <cstdlib>
#include <string_view>

#include "engine/core/log.h"

namespace lantern::runtime {
namespace {

bool env_flag(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && std::string_view(value) != "0" && std::string_view(value) != "";
}

}  // namespace

ValidationRequest resolve_validation_request(bool option_validation, bool option_sync) {
  ValidationRequest request;
  request.synchronization = option_sync || env_flag("LANTERN_SYNC_VALIDATION");
  request.validation =
      option_validation || request.synchronization || env_flag("LANTERN_VALIDATION");
#ifndef NDEBUG
  request.validation = true;
#endif
  return request;
}

VKAPI_ATTR VkBool32 VKAPI_CALL validation_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT types,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user_data) {
  auto* counters = static_cast<ValidationCounters*>(user_data);
  const char* message =
      data != nullptr && data->pMessage != nullptr ? data->pMessage : "(no message)";
  if ((severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0) {
    counters->errors.fetch_add(1, std::memory_order_relaxed);
    log::error("vulkan validation: {}", message);
  } else if ((severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) != 0) {
    if ((types & VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT) != 0) {
      counters->performance_warnings.fetch_add(1, std::memory_order_relaxed);
      if (counters->print_performance) log::warn("vulkan performance: {}", message);
    } else {
      counters->warnings.fetch_add(1, std::memory_order_relaxed);
      log::warn("vulkan validation: {}", message);
    }
  }
  return VK_FALSE;  // never abort the call: the counters make tests fail instead
}

VkDebugUtilsMessengerCreateInfoEXT messenger_create_info(ValidationCounters* counters) {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = validation_callback;
  info.pUserData = counters;
  return info;
}

}  // namespace lantern::runtime
