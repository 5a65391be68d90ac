#pragma once
// The timeline along the bottom of the window: play/pause, rewind, the frame slider of the
// reference take, time and rate, speed and loop.
#include "ui/panel.h"

namespace mostyle::ui {

class PlaybackPanel : public Panel {
 public:
  void draw(EditorState& state) override;
};

}  // namespace mostyle::ui
