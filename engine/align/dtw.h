#pragma once
// Dynamic time warping of two feature series as the paper's section 3.2 uses it (Euclidean local
// cost, steps (1,0), (0,1), (1,1), end to end): the optimal monotone alignment of their frames.
// `--dtw paper` aligns with it to reproduce the paper; the default is slope_dtw.h.
#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

#include "engine/base/job_control.h"

namespace mostyle {

struct DtwOptions {
  int band = -1;  // Sakoe-Chiba half-width in frames around the scaled diagonal; -1: no band
  // Bytes the path search may spend on back-pointers (2 bits per cell in the band). Above it the
  // search divides and conquers (about twice the time, no extra memory); tests set it tiny.
  std::size_t pointer_budget_bytes = std::size_t{256} << 20;
};

struct DtwPath {
  std::vector<std::pair<int, int>> steps;  // (i, j), monotone, (0,0) .. (n-1,m-1)
  double cost = 0.0;                        // sum of local costs along steps, feature units
};

// Aligns a (n x d) and b (m x d), rows = frames, columns = features in any one unit. The local
// cost of frames i and j is the Euclidean distance of a.row(i) and b.row(j); D(i,j) = c(i,j) +
// min(D(i-1,j), D(i,j-1), D(i-1,j-1)); the path runs from (0,0) to (n-1,m-1) with steps (1,0),
// (0,1), (1,1) and its cost D(n-1,m-1) is the least possible.
// With a band, cell (i,j) is allowed when |j - i*(m-1)/(n-1)| <= band (every j when n == 1).
// Throws InputError on empty input, a column mismatch, a non-finite value, a band other than
// -1 that is negative or too narrow to connect (0,0) to (n-1,m-1) (the message gives the least
// band that would), or a cost that overflows. Throws Cancelled when `control` asks for it.
// Time O(n*m*d) (O(band*n*d) with a band); memory O(n + m) for the cost rows plus 2 bits per
// cell for the back-pointers while they fit pointer_budget_bytes, else O(n + m) in all.
DtwPath align_dtw(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const DtwOptions& o = {},
                  JobControl* control = nullptr);

// For each frame i in 0..n-1 of a, the mean of the frames j of b the path matches to it, so b
// can be resampled onto a's timeline: n values, in b's frames (fractional). Throws InputError
// when n < 1 or the path leaves some i in 0..n-1 unmatched or has an (i, j) outside i in 0..n-1,
// j >= 0. O(n + path length).
Eigen::VectorXd warp_map(const DtwPath& path, int n);

namespace detail {
// Shared with slope_dtw.cpp. Throws InputError naming `name` when x is empty, too long to index
// or holds a non-finite value.
void check_series(const Eigen::MatrixXd& x, const char* name);
// Local costs |a_i - b_j| of frame i of a against frames [j, j + len) of b, into c[0, len).
void local_costs(const Eigen::MatrixXd& a, int i, const Eigen::MatrixXd& b, int j, int len, double* c);
}  // namespace detail

}  // namespace mostyle
