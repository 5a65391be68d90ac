#pragma once
// What the takes are mixed from and how, for any number of takes: k and sparsity
// (re-decomposition on the worker, with its progress), the mode (paper mode for two takes), the
// alignment, the options, the layers' weights per body part and per component (shared), basic
// motions (paper). The weights themselves are in the takes' panel (layers_panel.h).
#include "ui/model/engine_link.h"
#include "ui/panels/panel.h"

namespace mostyle::ui {

class ParametersPanel : public Panel {
 public:
  explicit ParametersPanel(EngineLink& engine) : engine_(engine) {}
  void draw(EditorState& state) override;

 private:
  EngineLink& engine_;
};

}  // namespace mostyle::ui
