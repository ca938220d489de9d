// RAII VkSurfaceKHR for a Window, created through GLFW on the Device's instance.
#pragma once

#include <vulkan/vulkan.h>

namespace lantern::runtime {

class Device;
class Window;

class Surface {
 public:
  // Throws lantern::RuntimeError when the surface cannot be made or the device's queue cannot
  // present to it.
  Surface(const Device& device, const Window& window);
  ~Surface();
  Surface(const Surface&) = delete;
  Surface& operator=(const Surface&) = delete;

  VkSurfaceKHR handle() const { return surface_; }

 private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
};

}  // namespace lantern::runtime
