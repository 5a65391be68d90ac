#pragma once
// The left-foot signals before and after warping with matched frames joined (paper Fig. 2), and
// the local-cost matrix with the optimal path. Hover: the matched frames; click: jump there.
#include "ui/model/blend_session.h"
#include "ui/panels/panel.h"

namespace mostyle::ui {

class DtwPanel : public Panel {
 public:
  explicit DtwPanel(BlendSession& session) : session_(session) {}
  void draw(EditorState& state) override;

 private:
  BlendSession& session_;
};

}  // namespace mostyle::ui
