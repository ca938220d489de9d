// Present modes by name (the `--set present_mode=...` spelling) and their Vulkan values.
#pragma once

#include <vulkan/vulkan.h>

#include <string_view>

namespace lantern::runtime {

// Fifo: vsync, never tears, always supported (the default). Mailbox: newest frame wins, no
// tearing, lower latency. Immediate: no waiting at all, may tear (benchmarks).
enum class PresentMode { Fifo, Mailbox, Immediate };

VkPresentModeKHR to_vk(PresentMode mode);
const char* present_mode_name(PresentMode mode);
// "fifo" | "mailbox" | "immediate"; lantern::InputError naming the accepted values otherwise.
PresentMode parse_present_mode(std::string_view name);

}  // namespace lantern::runtime
