#pragma once
// Pick a component: its joints light up on the result; its weight over time in each take; each
// take's reconstruction error against k from the decompositions seen so far.
#include "ui/model/blend_session.h"
#include "ui/panels/panel.h"

namespace mostyle::ui {

class ComponentsPanel : public Panel {
 public:
  explicit ComponentsPanel(BlendSession& session) : session_(session) {}
  void draw(EditorState& state) override;

 private:
  BlendSession& session_;
};

}  // namespace mostyle::ui
