#pragma once
// Slope-limited, open-ended DTW: the alignment the blend uses
// by default. The paper's plain DTW (dtw.h) lets one frame of a take match any number of frames
// of the other, so a warped take jumps over them; it also has to run from the first frames to
// the last, so extra material at either end (standing before the walk, a longer take) is
// squashed into the match. Here:
//   - every step advances both takes, by (1, 1), (1, k) or (k, 1) frames with k <= max_slope,
//     so neither runs more than max_slope times faster than the other anywhere;
//   - with open ends the path may start and end anywhere: each frame of either take that it
//     leaves out costs end_penalty instead of its match cost, so the path keeps the frames that
//     match better than the penalty and leaves out extra material at the ends.
#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

#include "engine/base/job_control.h"

namespace mostyle {

struct SlopeDtwOptions {
  // Neither take advances more than this many frames while the other advances one (2 to 4).
  // 2 covers the stride and phase differences of styled takes of one action (a limping stride
  // is 1.7 times a brisk one); beyond that a path starts to match one take's pose against a
  // stretch of the other that is not the same phase.
  int max_slope = 2;
  bool open_ends = true;
  // Cost of leaving out one frame of either take, in feature units; < 0: automatic. Automatic
  // runs twice: first (on every q-th frame of long takes, about 250 000 cells) with
  // kEndPenaltyMax times the median cost of frames at random phases (median_pair_cost), then with kEndPenaltyOfPath times the mean cost per frame along that
  // first path, kept between kEndPenaltyMin and kEndPenaltyMax times the random median: frames
  // at the ends that match several times worse than the rest of the match are left out, however
  // different the two styles are overall.
  double end_penalty = -1.0;
  // Bytes the back-pointers may take (4 bits a cell). Above it the rows are recomputed from
  // checkpoints (about twice the time, memory O(checkpoints x m)); tests set it tiny.
  std::size_t pointer_budget_bytes = std::size_t{256} << 20;
  void Validate() const;  // throws InputError
};

constexpr double kEndPenaltyMin = 0.5, kEndPenaltyMax = 1.0, kEndPenaltyOfPath = 2.5;

struct SlopeDtwPath {
  // Path vertices (i, j) in order; consecutive vertices differ by (1, 1), (1, k) or (k, 1).
  // The first and last give the matched ranges [first.first, last.first] of a and
  // [first.second, last.second] of b.
  std::vector<std::pair<int, int>> steps;
  double cost = 0.0;         // weighted match cost along the path (each frame matched counts once)
  double end_penalty = 0.0;  // the penalty used, feature units per frame left out
  double objective = 0.0;    // cost + end_penalty x frames left out: what the path minimises
};

// Aligns a (n x d) and b (m x d), rows = frames. Local cost c(i, j) = |a_i - b_j|. A step to
// (i, j) by (1, k) from (i-1, j-k) passes cells (i, j-k+1) .. (i, j) and costs
// 2 c(i, j-k+1) + c(i, j-k+2) + ... + c(i, j) (likewise (k, 1)), a start costs 2 c(i0, j0): each
// frame of either take the path covers is counted once. Closed ends: the path runs from (0, 0)
// to (n-1, m-1), which needs max(n, m) - 1 <= max_slope * (min(n, m) - 1). Open ends: anywhere
// to anywhere, the objective adding end_penalty per frame not covered. Deterministic (ties:
// diagonal first, then shorter steps). Throws InputError on empty input, a column mismatch, a
// non-finite value, bad options, or closed ends that no allowed path connects; Cancelled when
// `control` asks. Time O(n m (d + max_slope)); memory O(max_slope m) for costs plus 4 bits a
// cell for the path while that fits the budget, else checkpoints (twice the time).
SlopeDtwPath align_slope_dtw(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                             const SlopeDtwOptions& options = {}, JobControl* control = nullptr);

// The median of |a_i - b_j| over at most 64 x 64 evenly spaced pairs: what matching frames at
// random phases costs. O(64^2 d).
double median_pair_cost(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

}  // namespace mostyle
