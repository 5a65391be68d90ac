#include "app/editor/input_queue.h"

#include <algorithm>

namespace mostyle::app {
namespace {

bool is_modifier_key(int key) {
  // GLFW_KEY_LEFT_SHIFT (340) to GLFW_KEY_RIGHT_SUPER (347).
  return key >= 340 && key <= 347;
}

}  // namespace

std::vector<KeyEvent> InputQueue::take_frame(bool typing) {
  std::vector<KeyEvent> out;
  std::vector<int> changed;  // keys whose state this frame changes
  std::vector<int> typed;    // typing: keys whose presses typed characters this frame
  bool pressed = false;      // a key other than a modifier went down this frame (typing: one that typed nothing)
  const bool only_releases = after_shortcut_;
  after_shortcut_ = false;
  while (!events_.empty()) {
    const KeyEvent& e = events_.front();
    const bool press = e.kind == KeyEvent::Kind::kKey && e.action != kActionRelease;
    const bool shortcut = (e.mods & (kModControl | kModAlt | kModSuper)) != 0;
    // Typing: a press followed by its character (AltGr's too: GLFW gives none for a shortcut), a
    // release of such a key, a modifier going down or up (Shift) before any key that types nothing.
    const bool types = typing && !only_releases && !after_shortcut_ &&
                       ((press && !is_modifier_key(e.key) && events_.size() > 1 &&
                         events_[1].kind == KeyEvent::Kind::kChar) ||
                        (e.kind == KeyEvent::Kind::kKey && e.action == kActionRelease &&
                         std::find(typed.begin(), typed.end(), e.key) != typed.end()) ||
                        (e.kind == KeyEvent::Kind::kKey && is_modifier_key(e.key) && !shortcut && !pressed));
    if (types) {
      if (press && !is_modifier_key(e.key)) {
        if (pressed) break;  // after a key that typed nothing: the field reads characters first
        typed.push_back(e.key);
      }
    } else if (e.kind == KeyEvent::Kind::kChar) {
      // A character goes with its key's press (the frame that press is in) or alone.
      if (only_releases || after_shortcut_) break;
      if (typing && pressed) break;
    } else {
      const bool changes = e.action != kActionRepeat;
      const bool seen = std::find(changed.begin(), changed.end(), e.key) != changed.end();
      if (changes && seen) break;  // its second change: the next frame
      // A press is seen with the modifiers it came with: a modifier going up or down after it
      // (xdotool lets go of Ctrl before S) waits for the next frame.
      if (changes && pressed && is_modifier_key(e.key)) break;
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
