#pragma once
// The takes' layers in the bottom strip, one view for 2 to 16 takes. The "Takes" tab: a row per
// take with its colour, its weight (kept summing to 1) or in a transfer its strength (the content
// and the neutral named), its name and its own timeline, on which its structure shows (its rests
// shaded, its actions, its strokes or gait cycles banded), the frames the result plays of it and
// the frame it shows at the playhead, so that what was matched to what reads take by take; beside
// the rows the blend pad to drag among the takes and a body part's take. The "Alignment" tab: one
// take's alignment onto the reference (alignment_view.h), the take picked by clicking its name.
// Above both: mix or transfer, the ghosts, equal weights, and a transfer's content and neutral.
#include <glm/glm.hpp>
#include <vector>

#include "ui/model/engine_link.h"
#include "ui/model/dtw_image.h"
#include "ui/model/layer_parts.h"
#include "ui/panels/panel.h"

namespace mostyle::ui {

// The blend pad: n takes on a circle of radius 1 (the reference at the top, clockwise); a point
// on the pad gives each take a weight by inverse squared distance (a vertex: that take alone).
glm::vec2 pad_vertex(int take, int n);
std::vector<double> pad_weights(glm::vec2 point, int n);
// Where the pad's marker sits for given weights: their weighted mean of the vertices.
glm::vec2 pad_point(const std::vector<double>& weights);

class LayersPanel : public Panel {
 public:
  explicit LayersPanel(EngineLink& engine) : engine_(engine) {}
  void draw(EditorState& state) override;

  // The take the Alignment tab shows (1 .. N - 1).
  int aligned_take() const { return aligned_take_; }

 private:
  void draw_mode(EditorState& state, const PreparedTakes& p);
  void draw_transfer_takes(EditorState& state, const PreparedTakes& p);
  // The rows, the pad and the parts; the weights (or a transfer's strengths) shown at the playhead,
  // edited there when keyed (ui/model/keyed_weights.h).
  void draw_takes(EditorState& state, const PreparedTakes& p);
  // One take's row; true when its weight moved (weights set).
  bool draw_row(EditorState& state, const PreparedTakes& p, int take, std::vector<double>& weights);
  // The pad over `weights` (one per take); true when dragged (weights set from it).
  bool draw_pad(std::vector<double>& weights, int n);
  void draw_parts(EditorState& state, const PreparedTakes& p);
  void draw_alignment_tab(EditorState& state, const PreparedTakes& p);

  EngineLink& engine_;
  int aligned_take_ = 1;
  DtwCostImage image_;                     // of imaged_'s take imaged_take_, made once per take
  const PreparedTakes* imaged_ = nullptr;
  int imaged_take_ = 0;
};

}  // namespace mostyle::ui
