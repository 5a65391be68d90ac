#pragma once
// The blending editor's panels over a BlendSession (ui/blend_session.h): parameters, files,
// DTW view, components view, metrics. Each draws one ImGui window, reads the session's latest
// snapshot and asks the worker for work; none blocks.
#include <string>

#include "ui/blend_session.h"
#include "ui/panel.h"

namespace mostyle::ui {

// alpha (applied in the same frame), k and sparsity (re-decomposition on the worker, with its
// progress), mode, per-component alphas (shared), basic motions (paper), export.
class ParametersPanel : public Panel {
 public:
  explicit ParametersPanel(BlendSession& session) : session_(session) {}
  void draw(EditorState& state) override;

 private:
  BlendSession& session_;
  char export_path_[512] = "blend.bvh";
};

// Paths for A and B with Load, a small .bvh browser, recent files, dropped files, load errors.
class FilesPanel : public Panel {
 public:
  FilesPanel(BlendSession& session, std::string folder);
  void draw(EditorState& state) override;

 private:
  BlendSession& session_;
  std::string folder_;
  char path_a_[512] = "";
  char path_b_[512] = "";
  std::string synced_a_, synced_b_;  // the snapshot paths the fields were last filled from
};

// The left-foot signals before and after warping with matched frames joined (paper Fig. 2), and
// the local-cost matrix with the optimal path. Hover: the matched frames; click: jump there.
class DtwPanel : public Panel {
 public:
  explicit DtwPanel(BlendSession& session) : session_(session) {}
  void draw(EditorState& state) override;

 private:
  BlendSession& session_;
};

// Pick a component: its joints light up on the blend; its weights over time for A and B; the
// reconstruction error against k from the decompositions seen so far.
class ComponentsPanel : public Panel {
 public:
  explicit ComponentsPanel(BlendSession& session) : session_(session) {}
  void draw(EditorState& state) override;

 private:
  BlendSession& session_;
};

// Reconstruction error, bone-length error, foot sliding, stage times and the frame time.
class MetricsPanel : public Panel {
 public:
  explicit MetricsPanel(BlendSession& session) : session_(session) {}
  void draw(EditorState& state) override;

 private:
  BlendSession& session_;
};

}  // namespace mostyle::ui
