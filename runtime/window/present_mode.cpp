// Present-mode names and Vulkan values.
#include "runtime/window/present_mode.h"

#include <fmt/format.h>

#include "engine/core/error.h"

namespace lantern::runtime {

VkPresentModeKHR to_vk(PresentMode mode) {
  switch (mode) {
    case PresentMode::Fifo:
      return VK_PRESENT_MODE_FIFO_KHR;
    case PresentMode::Mailbox:
      return VK_PRESENT_MODE_MAILBOX_KHR;
    case PresentMode::Immediate:
      return VK_PRESENT_MODE_IMMEDIATE_KHR;
  }
  return VK_PRESENT_MODE_FIFO_KHR;
}

const char* present_mode_name(PresentMode mode) {
  switch (mode) {
    case PresentMode::Fifo:
      return "fifo";
    case PresentMode::Mailbox:
      return "mailbox";
    case PresentMode::Immediate:
      return "immediate";
  }
  return "?";
}

PresentMode parse_present_mode(std::string_view name) {
  for (PresentMode mode : {PresentMode::Fifo, PresentMode::Mailbox, PresentMode::Immediate})
    if (name == present_mode_name(mode)) return mode;
  throw InputError(
      fmt::format("unknown present mode '{}' (expected fifo, mailbox or immediate)", name));
}

}  // namespace lantern::runtime
