#pragma once
// What the takes are mixed from and how, for any number of takes: k and sparsity
// (re-decomposition on the worker, with its progress), the mode (paper mode for two takes), the
// alignment, the options, the layers' weights per body part and per component (shared), basic
// motions (paper). The weights themselves are in the takes' panel (layers_panel.h).
#include "ui/model/blend_session.h"
#include "ui/panels/panel.h"

namespace mostyle::ui {

class ParametersPanel : public Panel {
 public:
  explicit ParametersPanel(BlendSession& session) : session_(session) {}
  void draw(EditorState& state) override;

 private:
  BlendSession& session_;
};

}  // namespace mostyle::ui
