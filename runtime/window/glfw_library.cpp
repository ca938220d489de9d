// GLFW start-up and shut-down with error messages that say what to do.
#include "runtime/window/glfw_library.h"

#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <cstdlib>
#include <mutex>
#include <string>

#include "engine/core/error.h"
#include "engine/core/log.h"

namespace lantern::runtime {
namespace {

std::mutex g_mutex;
std::weak_ptr<GlfwLibrary> g_library;
std::string g_last_error = "no GLFW error";

void on_glfw_error(int code, const char* description) {
  g_last_error = fmt::format("{} (code 0x{:x})", description, code);
  log::debug("GLFW: {}", g_last_error);
}

}  // namespace

const char* last_glfw_error() {
  return g_last_error.c_str();
}

std::shared_ptr<GlfwLibrary> GlfwLibrary::acquire() {
  std::lock_guard lock(g_mutex);
  if (auto library = g_library.lock()) return library;
  glfwSetErrorCallback(on_glfw_error);
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display == nullptr || *display == '\0') && (wayland == nullptr || *wayland == '\0'))
    throw RuntimeError(
        "cannot open a window: DISPLAY is not set (no X server). Run under `xvfb-run -a`, or "
        "render headless");
  if (glfwInit() != GLFW_TRUE)
    throw RuntimeError(fmt::format("cannot open a window: glfwInit failed on DISPLAY='{}': {}",
                                   display != nullptr ? display : "", g_last_error));
  if (glfwVulkanSupported() != GLFW_TRUE) {
    glfwTerminate();
    throw RuntimeError(
        fmt::format("cannot open a window: GLFW found no Vulkan loader: {}", g_last_error));
  }
  std::shared_ptr<GlfwLibrary> library(new GlfwLibrary());
  g_library = library;
  return library;
}

GlfwLibrary::~GlfwLibrary() {
  glfwTerminate();
}

}  // namespace lantern::runtime
