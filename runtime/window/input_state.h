// Keyboard and mouse state of a Window, updated by its GLFW callbacks: what is held now, and
// what changed since the last poll (cursor movement, scroll), for a fly camera and ImGui.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace lantern::runtime {

struct InputState {
  // Indexed by GLFW key codes (GLFW_KEY_*, up to GLFW_KEY_LAST = 348).
  std::array<bool, 349> keys{};
  // Indexed by GLFW mouse button codes (GLFW_MOUSE_BUTTON_1..8).
  std::array<bool, 8> mouse_buttons{};
  double cursor_x = 0.0;  // window coordinates (screen units), origin top-left
  double cursor_y = 0.0;
  double cursor_dx = 0.0;  // movement since the last Window::poll_events()
  double cursor_dy = 0.0;
  double scroll_x = 0.0;  // scroll since the last Window::poll_events()
  double scroll_y = 0.0;
  bool cursor_known = false;  // false until the first cursor event (no jump on entry)

  bool key_down(int key) const {
    return key >= 0 && key < static_cast<int>(keys.size()) && keys[static_cast<std::size_t>(key)];
  }
  bool button_down(int button) const {
    return button >= 0 && button < static_cast<int>(mouse_buttons.size()) &&
           mouse_buttons[static_cast<std::size_t>(button)];
  }
};

}  // namespace lantern::runtime
