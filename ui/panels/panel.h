#pragma once
// The interface every editor panel implements. The app calls draw() once per frame, between
// ImGui::NewFrame() and ImGui::Render(), in the order panels were added. A panel draws its own
// ImGui window(s), reads the EditorState and the engine's results, and edits the document
// (EditorState::document), the playback or the view. It asks the engine for nothing: after the
// panels, the engine link (EngineLink::sync) does what the document's change makes stale.
// Loading takes is the one command a panel gives (EngineLink::load_files). Nothing blocks.
#include "ui/model/editor_state.h"

namespace mostyle::ui {

class Panel {
 public:
  virtual ~Panel() = default;
  virtual void draw(EditorState& state) = 0;
};

}  // namespace mostyle::ui
