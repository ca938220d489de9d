// PlayInput, scripted input (play_input.h).
#include "apps/lantern/play/play_input.h"

#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "engine/core/error.h"
#include "runtime/window/input_state.h"

namespace lantern::app {

bool PlayInput::key(int code) const {
  return code >= 0 && code < static_cast<int>(keys.size()) && keys[static_cast<std::size_t>(code)];
}

bool PlayInput::button(int b) const {
  return b >= 0 && b < static_cast<int>(buttons.size()) && buttons[static_cast<std::size_t>(b)];
}

bool pressed(const PlayInput& now, const PlayInput& before, int key) {
  return now.key(key) && !before.key(key);
}

int key_code(const std::string& raw) {
  std::string name = raw;
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  if (name.size() == 1 && name[0] >= 'A' && name[0] <= 'Z') return GLFW_KEY_A + (name[0] - 'A');
  if (name.size() == 1 && name[0] >= '0' && name[0] <= '9') return GLFW_KEY_0 + (name[0] - '0');
  if (name.size() >= 2 && name[0] == 'F' && std::isdigit(static_cast<unsigned char>(name[1]))) {
    const int n = std::atoi(name.c_str() + 1);
    if (n >= 1 && n <= 12) return GLFW_KEY_F1 + n - 1;
  }
  static const std::pair<const char*, int> kNamed[] = {
      {"SPACE", GLFW_KEY_SPACE},       {"ESCAPE", GLFW_KEY_ESCAPE},
      {"ESC", GLFW_KEY_ESCAPE},        {"ENTER", GLFW_KEY_ENTER},
      {"TAB", GLFW_KEY_TAB},           {"LEFT_SHIFT", GLFW_KEY_LEFT_SHIFT},
      {"SHIFT", GLFW_KEY_LEFT_SHIFT},  {"LEFT_CONTROL", GLFW_KEY_LEFT_CONTROL},
      {"CTRL", GLFW_KEY_LEFT_CONTROL}, {"UP", GLFW_KEY_UP},
      {"DOWN", GLFW_KEY_DOWN},         {"LEFT", GLFW_KEY_LEFT},
      {"RIGHT", GLFW_KEY_RIGHT},
  };
  for (const auto& [n, code] : kNamed)
    if (name == n) return code;
  return -1;
}

namespace {

int button_code(const std::string& name) {
  if (name == "left") return GLFW_MOUSE_BUTTON_LEFT;
  if (name == "right") return GLFW_MOUSE_BUTTON_RIGHT;
  if (name == "middle") return GLFW_MOUSE_BUTTON_MIDDLE;
  return -1;
}

}  // namespace

InputScript InputScript::parse(const std::string& text, const std::string& origin) {
  InputScript script;
  std::istringstream lines(text);
  std::string line;
  int line_no = 0;
  while (std::getline(lines, line)) {
    ++line_no;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (w.empty()) continue;
    const auto bad = [&](const std::string& why) {
      return InputError(fmt::format("{}:{}: {} in '{}'", origin, line_no, why, line));
    };
    if (w.size() < 3 || w[0] != "frame") throw bad("expected 'frame N EVENT ...'");
    ScriptEvent e;
    try {
      std::size_t used = 0;
      e.frame = std::stoull(w[1], &used);
      if (used != w[1].size()) throw std::invalid_argument("frame");
    } catch (const std::exception&) {
      throw bad(fmt::format("bad frame number '{}'", w[1]));
    }
    const auto number = [&](const std::string& s) {
      try {
        std::size_t used = 0;
        const double v = std::stod(s, &used);
        if (used != s.size()) throw std::invalid_argument("number");
        return v;
      } catch (const std::exception&) {
        throw bad(fmt::format("bad number '{}'", s));
      }
    };
    const std::string& what = w[2];
    if (what == "quit" && w.size() == 3) {
      e.kind = ScriptEvent::Kind::Quit;
      script.events_.push_back(e);
    } else if ((what == "key" || what == "mouse") && w.size() == 5) {
      e.kind = what == "key" ? ScriptEvent::Kind::Key : ScriptEvent::Kind::Button;
      e.code = what == "key" ? key_code(w[3]) : button_code(w[3]);
      if (e.code < 0) throw bad(fmt::format("unknown {} '{}'", what, w[3]));
      if (w[4] == "down" || w[4] == "up") {
        e.down = w[4] == "down";
        script.events_.push_back(e);
      } else if (w[4] == "press") {
        e.down = true;
        script.events_.push_back(e);
        e.down = false;
        ++e.frame;
        script.events_.push_back(e);
      } else {
        throw bad(fmt::format("expected down, up or press, got '{}'", w[4]));
      }
    } else if ((what == "move" || what == "cursor") && w.size() == 5) {
      e.kind = what == "move" ? ScriptEvent::Kind::Move : ScriptEvent::Kind::Cursor;
      e.x = number(w[3]);
      e.y = number(w[4]);
      script.events_.push_back(e);
    } else if (what == "scroll" && w.size() == 4) {
      e.kind = ScriptEvent::Kind::Scroll;
      e.y = number(w[3]);
      script.events_.push_back(e);
    } else {
      throw bad(fmt::format("unknown event '{}' or wrong number of words", what));
    }
  }
  std::stable_sort(script.events_.begin(), script.events_.end(),
                   [](const ScriptEvent& a, const ScriptEvent& b) { return a.frame < b.frame; });
  return script;
}

InputScript InputScript::load(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("--script: cannot read {}", path.string()));
  std::stringstream text;
  text << in.rdbuf();
  return parse(text.str(), path.string());
}

std::uint64_t InputScript::last_frame() const {
  return events_.empty() ? 0 : events_.back().frame;
}

void InputScript::apply(std::uint64_t frame, PlayInput& input) {
  for (const ScriptEvent& e : events_) {
    if (e.frame != frame) continue;
    switch (e.kind) {
      case ScriptEvent::Kind::Key:
        held_keys_[static_cast<std::size_t>(e.code)] = e.down;
        break;
      case ScriptEvent::Kind::Button:
        held_buttons_[static_cast<std::size_t>(e.code)] = e.down;
        break;
      case ScriptEvent::Kind::Move:
        input.cursor_dx += e.x;
        input.cursor_dy += e.y;
        cursor_x_ = (cursor_set_ ? cursor_x_ : input.cursor_x) + e.x;
        cursor_y_ = (cursor_set_ ? cursor_y_ : input.cursor_y) + e.y;
        cursor_set_ = true;
        break;
      case ScriptEvent::Kind::Cursor:
        input.cursor_dx += e.x - (cursor_set_ ? cursor_x_ : input.cursor_x);
        input.cursor_dy += e.y - (cursor_set_ ? cursor_y_ : input.cursor_y);
        cursor_x_ = e.x;
        cursor_y_ = e.y;
        cursor_set_ = true;
        break;
      case ScriptEvent::Kind::Scroll:
        input.scroll_y += e.y;
        break;
      case ScriptEvent::Kind::Quit:
        input.quit = true;
        break;
    }
  }
  for (std::size_t k = 0; k < held_keys_.size(); ++k)
    input.keys[k] = input.keys[k] || held_keys_[k];
  for (std::size_t b = 0; b < held_buttons_.size(); ++b)
    input.buttons[b] = input.buttons[b] || held_buttons_[b];
  if (cursor_set_) {
    input.cursor_x = cursor_x_;
    input.cursor_y = cursor_y_;
  }
}

PlayInput input_from_window(const runtime::InputState& state) {
  PlayInput input;
  input.keys = state.keys;
  input.buttons = state.mouse_buttons;
  input.cursor_x = state.cursor_x;
  input.cursor_y = state.cursor_y;
  if (state.cursor_known) {
    input.cursor_dx = state.cursor_dx;
    input.cursor_dy = state.cursor_dy;
  }
  input.scroll_y = state.scroll_y;
  return input;
}

}  // namespace lantern::app
