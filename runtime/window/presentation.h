// Device configuration for presenting to windows: the surface instance extensions GLFW needs and
// a per-queue-family presentation check, set on DeviceOptions before the Device is created.
//
//   runtime::DeviceOptions options{.selector = "auto"};
//   auto glfw = runtime::enable_presentation(options);  // throws without a display
//   runtime::Device device(options);
#pragma once

#include <memory>

#include "runtime/core/device.h"
#include "runtime/window/glfw_library.h"

namespace lantern::runtime {

// Adds the surface extensions and presentation check to `options`. The returned handle keeps
// GLFW initialised; hold it until the device is created (Window holds its own).
std::shared_ptr<GlfwLibrary> enable_presentation(DeviceOptions& options);

}  // namespace lantern::runtime
