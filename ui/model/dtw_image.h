#pragma once
// The alignment view's cost picture: the local-cost matrix of one take's alignment onto the
// reference (take 0), sampled at cell centres, for the alignment view to draw. Plain data, no ImGui.
#include <Eigen/Core>

#include "engine/align/prepare_takes.h"

namespace mostyle::ui {

// rows x cols cells (at most kMaxCells each way) over the reference's frames (rows) x the take's
// (cols).
struct DtwCostImage {
  static constexpr int kMaxCells = 64;
  int rows = 0, cols = 0;
  int frames_a = 0, frames_b = 0;
  Eigen::MatrixXf cost;  // rows x cols, local cost normalised to [0, 1]
};

// Local cost c(i, j) = |a_i - b_j| (the DTW's, engine/align/dtw.h) of take `take`'s alignment
// features at the centre of each cell: O(cells), not O(F x Fb), so a long take does not stall the
// frame that takes it up. Empty (no cells) for a take that is not there (or the reference) or
// without features.
DtwCostImage dtw_cost_image(const PreparedTakes& takes, int take = 1);

}  // namespace mostyle::ui
