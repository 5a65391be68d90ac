#pragma once
// Reconstruction error, bone-length error, foot sliding, stage times and the frame time.
#include "ui/blend_session.h"
#include "ui/panel.h"

namespace mostyle::ui {

class MetricsPanel : public Panel {
 public:
  explicit MetricsPanel(BlendSession& session) : session_(session) {}
  void draw(EditorState& state) override;

 private:
  BlendSession& session_;
};

}  // namespace mostyle::ui
