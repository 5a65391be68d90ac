#pragma once
// Paper mode's decompositions prepared for the synthesis (paper 3.6), once per decomposition
// (pair): the core components of each and the motions a blend moves between, which
// synthesize/synthesis.h mixes at each slider move.
#include <Eigen/Core>
#include <vector>

#include "engine/decompose/basic_motions.h"

namespace mostyle {

// Paper 3.6 "Components SVD": C = U S V^T (thin SVD), core component K = U S, so C = K V^T.
struct CoreComponents {
  Eigen::MatrixXd core;   // K = U S: k x k
  Eigen::MatrixXd basis;  // V: 3N x k, orthonormal columns
};

// SVD of components (k x 3N, k <= 3N), singular values in decreasing order. Signs are fixed
// so that each column of V has its largest-magnitude entry positive (the first such on ties):
// paper mode mixes K_B with V_A, which depends on that choice, so it must not be left to the
// SVD routine. Throws InputError when k > 3N or an entry is not finite. Cost O(k^2 * 3N).
CoreComponents core_components(const Eigen::MatrixXd& components);

// ---- Paper mode: X_syn = W_A ((1 - alpha) K_A + alpha K_B) V_A^T, exactly as written. ----
// Components of two separate decompositions do not correspond, so alpha = 1 is not B.
struct PaperSynthesis {
  Eigen::MatrixXd motion_a;  // W_A K_A V_A^T: frames x 3N (W_A C_A up to rounding)
  Eigen::MatrixXd motion_b;  // W_A K_B V_A^T: frames x 3N
};

// weights_a: W_A (frames x k). Only A's weights are used, so B may have any frame count; B's
// core must have the same k. Throws InputError on mismatched k or channel counts.
// Cost: two frames x k by k x 3N products.
PaperSynthesis prepare_paper_synthesis(const Eigen::MatrixXd& weights_a, const CoreComponents& a,
                                       const CoreComponents& b);
// ---- Paper mode, basic motions: X_syn = sum_i W^A_i K^A_i V^A_i^T with one level's core ----
// K^A_s replaced by K^B_s. We generalize the swap to a blend (1 - alpha) K^A_s + alpha K^B_s;
// alpha = 1 is the paper's swap. A's final residual is not included (the paper's formula has
// none); add BasicMotions::residual to out to reproduce A exactly at alpha = 0.
struct BasicMotionSynthesis {
  Eigen::MatrixXd motion_a;                 // sum_i W^A_i K^A_i V^A_i^T: frames x 3N
  std::vector<Eigen::MatrixXd> swap_delta;  // per level W^A_i (K^B_i - K^A_i) V^A_i^T: frames x 3N
};

// Both chains need the same number of levels, the same k and channel count; B's frame count is
// free. Throws InputError otherwise. Cost: 2m SVDs of k x 3N, 2m frames x k by k x 3N products.
BasicMotionSynthesis prepare_basic_motion_synthesis(const BasicMotions& a, const BasicMotions& b);

}  // namespace mostyle
