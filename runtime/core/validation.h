// Validation-layer policy and message counting: whether validation is wanted (option, env
// LANTERN_VALIDATION / LANTERN_SYNC_VALIDATION, debug build) and the debug-utils callback that
// counts errors, warnings and performance warnings for tests to assert on.
#pragma once

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>

namespace lantern::runtime {

// Message counts since the instance was created. Thread-safe: drivers may call back from any
// thread.
struct ValidationCounters {
  std::atomic<std::uint32_t> errors{0};
  std::atomic<std::uint32_t> warnings{0};
  std::atomic<std::uint32_t> performance_warnings{0};
  // Print performance warnings too (off by default: lavapipe triggers many harmless ones).
  bool print_performance = false;
};

struct ValidationRequest {
  bool validation = false;       // VK_LAYER_KHRONOS_validation
  bool synchronization = false;  // + synchronization validation (implies validation)
};

// Combines the caller's wishes with LANTERN_VALIDATION=1, LANTERN_SYNC_VALIDATION=1 and the build
// type (validation is always on in debug builds).
ValidationRequest resolve_validation_request(bool option_validation, bool option_sync);

// The messenger callback; user data must point to a ValidationCounters that outlives the messenger.
VKAPI_ATTR VkBool32 VKAPI_CALL validation_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT types,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user_data);

// A messenger create-info wired to validation_callback (errors, warnings, performance).
VkDebugUtilsMessengerCreateInfoEXT messenger_create_info(ValidationCounters* counters);

}  // namespace lantern::runtime
