// GLFW window creation, event processing and the callbacks that keep size and input current.
#include "runtime/window/window.h"

#include <vulkan/vulkan.h>
// GLFW must see the Vulkan header first to declare its Vulkan entry points.
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include "engine/core/error.h"

namespace lantern::runtime {

Window::Window(const WindowDesc& desc) {
  if (desc.width == 0 || desc.height == 0)
    throw InputError(fmt::format("window '{}': size {}x{} must be non-zero", desc.title, desc.width,
                                 desc.height));
  glfw_ = GlfwLibrary::acquire();
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);  // Vulkan presents; no OpenGL context
  glfwWindowHint(GLFW_RESIZABLE, desc.resizable ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_VISIBLE, desc.visible ? GLFW_TRUE : GLFW_FALSE);
  window_ = glfwCreateWindow(static_cast<int>(desc.width), static_cast<int>(desc.height),
                             desc.title.c_str(), nullptr, nullptr);
  if (window_ == nullptr)
    throw RuntimeError(fmt::format("cannot create window '{}' ({}x{}): {}", desc.title, desc.width,
                                   desc.height, last_glfw_error()));
  glfwSetWindowUserPointer(window_, this);
  int width = 0;
  int height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  framebuffer_ = {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height)};
  install_callbacks();
}

Window::~Window() {
  if (window_ != nullptr) glfwDestroyWindow(window_);
}

Window& Window::self(GLFWwindow* window) {
  return *static_cast<Window*>(glfwGetWindowUserPointer(window));
}

void Window::install_callbacks() {
  glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int width, int height) {
    Window& me = self(w);
    const FramebufferSize size{static_cast<std::uint32_t>(width),
                               static_cast<std::uint32_t>(height)};
    if (size == me.framebuffer_) return;
    me.framebuffer_ = size;
    ++me.resize_count_;
    if (me.resize_callback_) me.resize_callback_(size);
  });
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
    auto& keys = self(w).input_.keys;
    if (key < 0 || key >= static_cast<int>(keys.size())) return;  // GLFW_KEY_UNKNOWN
    if (action == GLFW_PRESS) keys[static_cast<std::size_t>(key)] = true;
    if (action == GLFW_RELEASE) keys[static_cast<std::size_t>(key)] = false;
  });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
    auto& buttons = self(w).input_.mouse_buttons;
    if (button < 0 || button >= static_cast<int>(buttons.size())) return;
    buttons[static_cast<std::size_t>(button)] = action == GLFW_PRESS;
  });
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
    InputState& input = self(w).input_;
    if (input.cursor_known) {
      input.cursor_dx += x - input.cursor_x;
      input.cursor_dy += y - input.cursor_y;
    }
    input.cursor_x = x;
    input.cursor_y = y;
    input.cursor_known = true;
  });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double dx, double dy) {
    self(w).input_.scroll_x += dx;
    self(w).input_.scroll_y += dy;
  });
}

void Window::poll_events() {
  input_.cursor_dx = input_.cursor_dy = 0.0;
  input_.scroll_x = input_.scroll_y = 0.0;
  glfwPollEvents();
}

void Window::wait_events(double timeout_s) {
  input_.cursor_dx = input_.cursor_dy = 0.0;
  input_.scroll_x = input_.scroll_y = 0.0;
  glfwWaitEventsTimeout(timeout_s);
}

bool Window::should_close() const {
  return glfwWindowShouldClose(window_) == GLFW_TRUE;
}

void Window::request_close() {
  glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

void Window::set_size(std::uint32_t width, std::uint32_t height) {
  if (width == 0 || height == 0)
    throw InputError(fmt::format("window size {}x{} must be non-zero", width, height));
  glfwSetWindowSize(window_, static_cast<int>(width), static_cast<int>(height));
}

void Window::set_title(const std::string& title) {
  glfwSetWindowTitle(window_, title.c_str());
}

void Window::capture_cursor(bool captured) {
  glfwSetInputMode(window_, GLFW_CURSOR, captured ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
  if (captured && glfwRawMouseMotionSupported() == GLFW_TRUE)
    glfwSetInputMode(window_, GLFW_RAW_MOUSE_MOTION, GLFW_TRUE);
  cursor_captured_ = captured;
  input_.cursor_known = false;  // the next position is a new origin, not a jump
}

}  // namespace lantern::runtime
