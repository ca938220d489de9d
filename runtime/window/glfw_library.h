// Process-wide GLFW initialisation, shared by every Window and by presentation setup: the first
// acquire() initialises GLFW (no client API: Vulkan only), the last release terminates it.
#pragma once

#include <memory>

namespace lantern::runtime {

class GlfwLibrary {
 public:
  // Throws lantern::RuntimeError naming the cause when GLFW cannot start (no DISPLAY, no X
  // server, no Vulkan loader); headless rendering needs no GLFW at all.
  static std::shared_ptr<GlfwLibrary> acquire();
  ~GlfwLibrary();
  GlfwLibrary(const GlfwLibrary&) = delete;
  GlfwLibrary& operator=(const GlfwLibrary&) = delete;

 private:
  GlfwLibrary() = default;
};

// The last GLFW error as "description (code 0x...)", or "no GLFW error" (for messages).
const char* last_glfw_error();

}  // namespace lantern::runtime
