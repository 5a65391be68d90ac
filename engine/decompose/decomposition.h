#pragma once
// Sparse coding-based decomposition (paper 3.4, after SPLOCS): a normalized motion matrix X
// (frames x 3N) is factored as X ~ W C, with weights W (frames x k) and sparse, localized
// components C (k x 3N).
#include <Eigen/Core>
#include <vector>

#include "engine/base/job_control.h"

namespace mostyle {

struct DecompositionOptions {
  int components = 10;    // k, 1 <= k <= 3N
  // f in (0, 1]: each component row of C keeps max(1, round(f * 3N)) non-zero channels, so the
  // overall non-zero fraction of C is f whenever f * 3N is whole, and no component is empty.
  double sparsity = 0.1;
  int max_iterations = 100;  // alternating W / C rounds after the greedy init, >= 0
  double tolerance = 1e-6;   // stop when |E_prev - E| < tolerance * E_prev, E the objective
  // Sparse-coding sweeps per C update, >= 1: warm-started, each sweep updates every component
  // row once (sparse_code_normal with SparseGroup::kRow).
  int sparse_coding_iterations = 5;
  // Local components (SPLOCS's support maps, on the skeleton): when given (one parent per joint,
  // -1 for a root; 3N / 3 entries), each component's support is whole joints forming one
  // connected piece of the skeleton around its centre, max(1, round(f * 3N / 3)) joints.
  // Empty: channels anywhere, the largest ones (the paper's plain sparsity).
  std::vector<int> locality_parents;

  // Throws InputError when an option is out of range for x (frames x 3N), or x is empty, has a
  // column count that is not a multiple of 3, or holds a NaN or infinite value.
  void Validate(const Eigen::MatrixXd& x) const;
  // Non-zeros kept per component row for `channels` (= 3N) columns: max(1, round(f * 3N)).
  int NonzerosPerComponent(int channels) const;
};

struct Decomposition {
  Eigen::MatrixXd weights;     // W: frames x k; every non-zero column has max |w| = 1
  Eigen::MatrixXd components;  // C: k x 3N, NonzerosPerComponent(3N) entries kept per row
  int iterations = 0;          // alternating rounds run
  bool converged = false;      // the tolerance was met before the iteration cap
  double objective = 0.0;      // ||X - W C||_F^2, X's units squared
  double rmse = 0.0;           // sqrt(objective / (frames * 3N)), X's units
  double nonzero_fraction = 0.0;  // non-zero entries of C / (k * 3N)
  double elapsed_ms = 0.0;        // wall time of the call
  // Objective after the greedy init, then after each round (size iterations + 1); never
  // increases from one entry to the next, up to rounding.
  std::vector<double> objective_history;
};

// Decomposes x (frames x 3N, normalized, joints as consecutive x, y, z triples). Deterministic.
// Greedy init: k times, the joint with the most residual energy gives a weight column (the
// rank-1 SVD of its trajectory) and its component entries; a budget beyond 3 channels goes to
// the channels that weight explains best. Then alternating rounds of closed-form weight updates
// (projected to max |w| = 1, the component scaled inversely) and sparse-coding component
// updates, each of which can only lower the objective.
// control (may be null): checked for cancel once per round (throws Cancelled), progress 0..1.
// Throws InputError from options.Validate(x).
// Cost per round: O(frames * k * 3N) (one product W^T X), plus O(frames * nnz(C)).
Decomposition decompose(const Eigen::MatrixXd& x, const DecompositionOptions& options = {},
                        JobControl* control = nullptr);

// Shared components (ours, the default; the paper decomposes each take apart, whose components
// do not correspond) for any number of takes: one C for the stacked [x_0; ...; x_n-1] (frame counts may differ, channel counts must match), W_i per take.
struct StackedDecomposition {
  std::vector<Eigen::MatrixXd> weights;  // W_i: frames_i x k, one per take
  Eigen::MatrixXd components;            // C: k x 3N, shared
  int iterations = 0;
  bool converged = false;
  double objective = 0.0;                // sum_i ||x_i - W_i C||_F^2
  std::vector<double> rmse;              // per take, x's units
  double nonzero_fraction = 0.0;
  double elapsed_ms = 0.0;
  std::vector<double> objective_history;
};

// Throws InputError (naming the take, 1-based) when fewer than one take is given, the channel
// counts differ, or options.Validate fails on a take.
// Same cost as decompose() on the sum of the frames.
StackedDecomposition decompose_stacked(const std::vector<const Eigen::MatrixXd*>& takes,
                                       const DecompositionOptions& options = {}, JobControl* control = nullptr);

namespace detail {
// decompose() reporting its progress inside [progress_begin, progress_end] of the job, for jobs
// that chain several decompositions (basic motions).
Decomposition decompose_part(const Eigen::MatrixXd& x, const DecompositionOptions& options,
                             JobControl* control, float progress_begin, float progress_end);
}  // namespace detail

}  // namespace mostyle
