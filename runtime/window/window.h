// runtime::Window: one GLFW window without a client API (Vulkan presents to it), with its
// framebuffer size, minimise state, close request and input. Events are processed only in
// poll_events()/wait_events(), on the thread that created the window (a GLFW rule).
//
//   runtime::Window window({.title = "lantern", .width = 640, .height = 360});
//   while (!window.should_close()) { window.poll_events(); if (window.minimized()) continue; ... }
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "runtime/window/glfw_library.h"
#include "runtime/window/input_state.h"

struct GLFWwindow;

namespace lantern::runtime {

struct WindowDesc {
  std::string title = "lantern";
  std::uint32_t width = 640;  // window size in screen units
  std::uint32_t height = 360;
  bool resizable = true;
  bool visible = true;
};

struct FramebufferSize {
  std::uint32_t width = 0;  // pixels; 0 x 0 while minimised
  std::uint32_t height = 0;
  friend bool operator==(const FramebufferSize&, const FramebufferSize&) = default;
};

class Window {
 public:
  // Throws lantern::RuntimeError when there is no display (see GlfwLibrary::acquire) or the
  // window cannot be created; InputError for a zero size.
  explicit Window(const WindowDesc& desc = {});
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  // Processes pending events; resets the per-poll deltas (cursor movement, scroll) first.
  void poll_events();
  // Blocks until an event arrives or `timeout_s` passes (for idling while minimised).
  void wait_events(double timeout_s);

  FramebufferSize framebuffer_size() const { return framebuffer_; }
  // True while the framebuffer is 0 x 0 (iconified): render nothing, recreate nothing.
  bool minimized() const { return framebuffer_.width == 0 || framebuffer_.height == 0; }
  // Counts framebuffer-size changes reported by GLFW since creation.
  std::uint64_t resize_count() const { return resize_count_; }
  // Called from poll_events() when the framebuffer size changes (also to 0 x 0).
  void on_framebuffer_resize(std::function<void(FramebufferSize)> callback) {
    resize_callback_ = std::move(callback);
  }

  bool should_close() const;
  void request_close();
  // Asks the window system for a new window size (screen units); the framebuffer follows when
  // events are processed.
  void set_size(std::uint32_t width, std::uint32_t height);
  void set_title(const std::string& title);
  // Hides the cursor and reports unbounded movement (fly camera); false restores it.
  void capture_cursor(bool captured);
  bool cursor_captured() const { return cursor_captured_; }

  const InputState& input() const { return input_; }
  // For ImGui's GLFW backend and anything else that needs GLFW directly. Installing ImGui's
  // callbacks with chaining keeps this class's callbacks working.
  GLFWwindow* handle() const { return window_; }

 private:
  static Window& self(GLFWwindow* window);
  void install_callbacks();

  std::shared_ptr<GlfwLibrary> glfw_;
  GLFWwindow* window_ = nullptr;
  FramebufferSize framebuffer_;
  std::uint64_t resize_count_ = 0;
  std::function<void(FramebufferSize)> resize_callback_;
  InputState input_;
  bool cursor_captured_ = false;
};

}  // namespace lantern::runtime
