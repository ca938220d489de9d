// One frame of input for `lantern play`: the window's keyboard/mouse state (runtime::InputState)
// merged with scripted events (`--script FILE`), so tests drive exactly the path GLFW feeds.
//
// Script format, one event per line ('#' starts a comment):
//   frame N key NAME down|up|press   (press = down on frame N, up on frame N+1)
//   frame N mouse left|right|middle down|up|press
//   frame N move DX DY               (cursor movement in window units)
//   frame N cursor X Y               (absolute cursor position, window units)
//   frame N scroll DY
//   frame N quit
// Key NAMEs: A..Z, 0..9, F1..F12, SPACE, ESCAPE, ENTER, TAB, LEFT_SHIFT (alias SHIFT),
// LEFT_CONTROL (alias CTRL), UP, DOWN, LEFT, RIGHT. Frames count from 0 (frames rendered).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace lantern::runtime {
struct InputState;
}

namespace lantern::app {

struct PlayInput {
  std::array<bool, 349> keys{};   // GLFW key codes
  std::array<bool, 8> buttons{};  // GLFW mouse buttons (0 left, 1 right, 2 middle)
  double cursor_x = 0.0;          // window units, origin top-left
  double cursor_y = 0.0;
  double cursor_dx = 0.0;  // since last frame
  double cursor_dy = 0.0;
  double scroll_y = 0.0;
  bool quit = false;

  bool key(int code) const;
  bool button(int b) const;
};

// Key down this frame and up last frame.
bool pressed(const PlayInput& now, const PlayInput& before, int key);

struct ScriptEvent {
  std::uint64_t frame = 0;
  enum class Kind { Key, Button, Move, Cursor, Scroll, Quit } kind = Kind::Key;
  int code = 0;       // key or button
  bool down = false;  // key/button
  double x = 0.0;     // move/cursor/scroll
  double y = 0.0;
};

class InputScript {
 public:
  InputScript() = default;
  // lantern::InputError naming the file and line for a bad line.
  static InputScript parse(const std::string& text, const std::string& origin);
  static InputScript load(const std::filesystem::path& path);

  // Applies the events of `frame` on top of `input` (held script keys stay down until their up).
  void apply(std::uint64_t frame, PlayInput& input);
  bool empty() const { return events_.empty(); }
  std::uint64_t last_frame() const;

 private:
  std::vector<ScriptEvent> events_;
  std::array<bool, 349> held_keys_{};
  std::array<bool, 8> held_buttons_{};
  double cursor_x_ = 0.0;
  double cursor_y_ = 0.0;
  bool cursor_set_ = false;
};

// The window's state as a PlayInput.
PlayInput input_from_window(const runtime::InputState& state);

// GLFW key code for a script NAME, -1 if unknown.
int key_code(const std::string& name);

}  // namespace lantern::app
