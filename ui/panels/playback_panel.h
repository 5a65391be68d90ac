#pragma once
// The timeline along the bottom of the window: the Keys button, play/pause, rewind, speed, loop,
// time and rate, the Set key button, and the frame slider of the reference take with its marks: ticks
// where the reference's cycles begin, and the weight keys (style over time,
// ui/model/keyed_weights.h) as diamonds to drag in time, click to go to, right-click to delete,
// hover for their time and weights. Hovering the slider elsewhere tells where the output cycle
// under the mouse came from: which cycle of each take, in its own file (ui/model/cycle_provenance.h),
// and underlines that cycle. Keys, not while a text field or a slider has the keyboard:
// space plays and pauses, the left and right arrows step one frame, K keys the weights at the
// playhead, Delete removes the key under the mouse (else the one at the playhead).
#include "ui/panels/panel.h"

namespace mostyle::ui {

class PlaybackPanel : public Panel {
 public:
  void draw(EditorState& state) override;
  // The span of EditorState::cycle_provenance the slider's tooltip told of in the last frame
  // drawn; -1: none (the mouse elsewhere, over a key's mark, or no result yet).
  int hovered_span() const { return hovered_span_; }

 private:
  int hovered_span_ = -1;
  bool mark_dragged_ = false;  // the key's mark held was dragged: letting go is not a click
};

}  // namespace mostyle::ui
