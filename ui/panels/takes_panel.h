#pragma once
// The "Takes" window: each loaded take with its colour, visibility and size, load errors and
// warnings as the engine worded them (folded, inside the panel), Frame all, and the viewport's
// display toggles.
#include "ui/panels/panel.h"

namespace mostyle::ui {

class TakesPanel : public Panel {
 public:
  void draw(EditorState& state) override;
};

}  // namespace mostyle::ui
