#pragma once
// alpha (applied in the same frame), k and sparsity (re-decomposition on the worker, with its
// progress), mode, per-component alphas (shared), basic motions (paper).
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
