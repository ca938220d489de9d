// The VkInstance with its optional validation layer and debug-utils messenger. Owned by Device;
// also created bare (no validation) by Device::enumerate() to list devices.
#pragma once

#include <vulkan/vulkan.h>

#include <memory>
#include <span>

#include "runtime/core/validation.h"

namespace lantern::runtime {

class Instance {
 public:
  // `extensions`: extra instance extensions (e.g. surface extensions); missing ones are errors.
  explicit Instance(ValidationRequest request, std::span<const char* const> extensions = {});
  ~Instance();
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;

  VkInstance handle() const { return instance_; }
  // True when the validation layer is actually loaded (false when requested but not installed).
  bool validation_enabled() const { return validation_enabled_; }
  bool sync_validation_enabled() const { return sync_validation_enabled_; }
  // VK_EXT_debug_utils is enabled: object names and command labels work.
  bool debug_utils() const { return debug_utils_; }
  const ValidationCounters& counters() const { return *counters_; }
  ValidationCounters& counters() { return *counters_; }

 private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  std::unique_ptr<ValidationCounters> counters_ = std::make_unique<ValidationCounters>();
  bool validation_enabled_ = false;
  bool sync_validation_enabled_ = false;
  bool debug_utils_ = false;
};

}  // namespace lantern::runtime
