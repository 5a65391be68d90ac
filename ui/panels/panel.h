#pragma once
// The interface every editor panel implements. The app calls draw() once per frame, between
// ImGui::NewFrame() and ImGui::Render(), in the order panels were added. A panel draws its own
// ImGui window(s), reads and changes the EditorState, and must not block: long work goes to
// the engine's worker and is polled here on later frames.
#include "ui/model/editor_state.h"

namespace mostyle::ui {

class Panel {
 public:
  virtual ~Panel() = default;
  virtual void draw(EditorState& state) = 0;
};

}  // namespace mostyle::ui
