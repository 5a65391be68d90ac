#pragma once
// The style palette panel, shown in the bottom strip instead of the DTW view while a
// palette of three or more takes is loaded: the takes with their colours, a weight each (kept
// summing to 1), a blend pad to drag among them, weights per body part, a transfer mode
// (content, neutral and style takes, a strength per style) and the warped ghosts.
#include <glm/glm.hpp>
#include <vector>

#include "ui/model/blend_session.h"
#include "ui/panels/panel.h"

namespace mostyle::ui {

// Weights after take i's weight was set to `value`: the others scaled so that all sum to 1 (or,
// when they sum to 0, sharing the rest equally), each kept within [lo, hi]. Pure, for tests.
std::vector<double> set_weight_keeping_sum(std::vector<double> weights, int i, double value, double lo = -0.5,
                                           double hi = 1.5);

// The blend pad: n takes on a circle of radius 1 (the reference at the top, clockwise); a point
// on the pad gives each take a weight by inverse squared distance (a vertex: that take alone).
glm::vec2 pad_vertex(int take, int n);
std::vector<double> pad_weights(glm::vec2 point, int n);
// Where the pad's marker sits for given weights: their weighted mean of the vertices.
glm::vec2 pad_point(const std::vector<double>& weights);

class PalettePanel : public Panel {
 public:
  explicit PalettePanel(BlendSession& session) : session_(session) {}
  void draw(EditorState& state) override;

 private:
  // The weights (or a transfer's strengths) shown at the playhead, edited there when keyed
  // (ui/model/keyed_weights.h).
  void draw_mix(EditorState& state, const PreparedTakes& p);
  // The pad over `weights` (one per take); true when dragged (weights set from it).
  bool draw_pad(std::vector<double>& weights, int n);
  void draw_parts(PaletteControls& c, const PreparedTakes& p);
  void draw_transfer(EditorState& state, const PreparedTakes& p);
  BlendSession& session_;
};

}  // namespace mostyle::ui
