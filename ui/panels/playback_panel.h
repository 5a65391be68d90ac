#pragma once
// The timeline along the bottom of the window: the Keys button, play/pause, rewind, the frame
// slider of the reference take, time and rate, speed and loop. Space plays and pauses, the left
// and right arrow keys step one frame (not while a text field or a slider has the keyboard).
#include "ui/panels/panel.h"

namespace mostyle::ui {

class PlaybackPanel : public Panel {
 public:
  void draw(EditorState& state) override;
};

}  // namespace mostyle::ui
