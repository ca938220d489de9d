// Surface creation and the queue's presentation check.
#include "runtime/window/surface.h"

#include <vulkan/vulkan.h>
// GLFW must see the Vulkan header first to declare its Vulkan entry points.
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include "engine/core/error.h"
#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"
#include "runtime/window/window.h"

namespace lantern::runtime {

Surface::Surface(const Device& device, const Window& window) : instance_(device.instance()) {
  VK_CHECK(glfwCreateWindowSurface(instance_, window.handle(), nullptr, &surface_));
  VkBool32 supported = VK_FALSE;
  const VkResult result = vkGetPhysicalDeviceSurfaceSupportKHR(
      device.physical_device(), device.queue_family(), surface_, &supported);
  if (result != VK_SUCCESS || supported != VK_TRUE) {
    vkDestroySurfaceKHR(instance_, surface_, nullptr);
    throw RuntimeError(fmt::format(
        "device '{}' cannot present to this window from queue family {} ({}); create the "
        "Device with runtime::enable_presentation()",
        device.info().name, device.queue_family(), vk_result_name(result)));
  }
}

Surface::~Surface() {
  vkDestroySurfaceKHR(instance_, surface_, nullptr);
}

}  // namespace lantern::runtime
