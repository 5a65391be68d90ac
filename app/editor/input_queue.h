#pragma once
// Keyboard input handed to ImGui at the pace of frames. Dear ImGui 1.86 reads keys as states
// (io.KeysDown) once a frame, so a key pressed and released between two frames, or pressed again
// before a frame saw its release, is a press the editor never sees; and characters typed right
// after a shortcut reach the frame before the field the shortcut opens can take them. The
// window platform queues every key and character event here, and each frame takes the events
// that keep each change visible: at most one press, no key changing twice, nothing but
// releases in the frame after a shortcut (a press with Ctrl, Alt or Super). While a text field
// has the keyboard, what was typed goes in one frame, whole: a path typed quickly and then a
// click on Load (the mouse is not queued) loads the path as typed, however slow the frames.
// Plain data: no GLFW, no ImGui, so tests feed it by hand.
#include <cstddef>
#include <deque>
#include <vector>

namespace mostyle::app {

struct KeyEvent {
  enum class Kind { kKey, kChar };
  Kind kind = Kind::kKey;
  int key = 0, scancode = 0, action = 0, mods = 0;  // kKey: as GLFW gives them
  unsigned codepoint = 0;                           // kChar
};

// GLFW's values (app/editor/window_platform.cpp checks them at compile time).
constexpr int kActionRelease = 0, kActionPress = 1, kActionRepeat = 2;
constexpr int kModShift = 0x1, kModControl = 0x2, kModAlt = 0x4, kModSuper = 0x8;

class InputQueue {
 public:
  void push(const KeyEvent& e) { events_.push_back(e); }
  bool empty() const { return events_.empty(); }
  std::size_t size() const { return events_.size(); }
  // The events for the next frame, oldest first, removed from the queue. typing: a text field has
  // the keyboard (ImGui's io.WantTextInput, of the frame before): then every character typed
  // (with the presses, Shift's too, and releases of the keys that typed it) goes in this frame, up
  // to a press that types nothing (Enter, Backspace, an arrow), which is taken last (a field
  // reads the frame's characters before its keys) and ends the frame's typing. O(events taken).
  std::vector<KeyEvent> take_frame(bool typing = false);

 private:
  std::deque<KeyEvent> events_;
  bool after_shortcut_ = false;  // the last frame took a press with Ctrl, Alt or Super
};

}  // namespace mostyle::app
