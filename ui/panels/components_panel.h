#pragma once
// Pick a component: its joints light up on the result; its weight over time in each take; each
// take's reconstruction error against k from the decompositions seen so far.
#include "ui/model/engine_link.h"
#include "ui/panels/panel.h"

namespace mostyle::ui {

class ComponentsPanel : public Panel {
 public:
  explicit ComponentsPanel(EngineLink& engine) : engine_(engine) {}
  void draw(EditorState& state) override;

 private:
  EngineLink& engine_;
};

}  // namespace mostyle::ui
