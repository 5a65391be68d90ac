#pragma once
// The timeline along the bottom of the window: the Keys button, play/pause, rewind, speed, loop,
// time and rate, the Set key button, and the frame slider of the reference take with its marks: ticks
// where the reference's cycles begin, and the weight keys (style over time,
// ui/model/keyed_weights.h) as diamonds to drag in time, click to go to, right-click to delete,
// hover for their time and weights. Keys, not while a text field or a slider has the keyboard:
// space plays and pauses, the left and right arrows step one frame, K keys the weights at the
// playhead, Delete removes the key under the mouse (else the one at the playhead).
#include "ui/panels/panel.h"

namespace mostyle::ui {

class PlaybackPanel : public Panel {
 public:
  void draw(EditorState& state) override;

 private:
  bool mark_dragged_ = false;  // the key's mark held was dragged: letting go is not a click
};

}  // namespace mostyle::ui
