#include "app/input_queue.h"

#include <algorithm>

namespace mostyle::app {
namespace {

bool is_modifier_key(int key) {
  // GLFW_KEY_LEFT_SHIFT (340) to GLFW_KEY_RIGHT_SUPER (347).
  return key >= 340 && key <= 347;
}

}  // namespace

std::vector<KeyEvent> InputQueue::take_frame() {
  std::vector<KeyEvent> out;
  std::vector<int> changed;  // keys whose state this frame changes
  bool pressed = false;      // a key other than a modifier went down this frame
  const bool only_releases = after_shortcut_;
  after_shortcut_ = false;
  while (!events_.empty()) {
    const KeyEvent& e = events_.front();
    if (e.kind == KeyEvent::Kind::kChar) {
      // A character goes with its key's press (the frame that press is in) or alone.
      if (only_releases || after_shortcut_) break;
    } else {
      const bool changes = e.action != kActionRepeat;
      const bool seen = std::find(changed.begin(), changed.end(), e.key) != changed.end();
      if (changes && seen) break;  // its second change: the next frame
      // A press is seen with the modifiers it came with: a modifier going up or down after it
      // (xdotool lets go of Ctrl before S) waits for the next frame.
      if (changes && pressed && is_modifier_key(e.key)) break;
      const bool press = e.action != kActionRelease;
      if (press && !is_modifier_key(e.key)) {
        if (only_releases || pressed) break;
        pressed = true;
        if (e.mods & (kModControl | kModAlt | kModSuper)) after_shortcut_ = true;
      }
      if (changes) changed.push_back(e.key);
    }
    out.push_back(e);
    events_.pop_front();
  }
  return out;
}

}  // namespace mostyle::app
