// Surface extensions and the presentation check from GLFW.
#include "runtime/window/presentation.h"

#include <vulkan/vulkan.h>
// GLFW must see the Vulkan header first to declare its Vulkan entry points.
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <string_view>

#include "engine/core/error.h"

namespace lantern::runtime {

std::shared_ptr<GlfwLibrary> enable_presentation(DeviceOptions& options) {
  auto library = GlfwLibrary::acquire();
  std::uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  if (names == nullptr)
    throw RuntimeError(
        fmt::format("cannot present: GLFW knows no Vulkan surface extensions for this display: {}",
                    last_glfw_error()));
  for (std::uint32_t i = 0; i < count; ++i) {
    bool listed = false;
    for (const char* have : options.instance_extensions)
      listed = listed || std::string_view(have) == names[i];
    if (!listed) options.instance_extensions.push_back(names[i]);
  }
  options.presentation_support = [](VkInstance instance, VkPhysicalDevice device,
                                    std::uint32_t family) {
    return glfwGetPhysicalDevicePresentationSupport(instance, device, family) == GLFW_TRUE;
  };
  return library;
}

}  // namespace lantern::runtime
