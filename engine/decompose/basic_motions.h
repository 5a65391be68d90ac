#pragma once
// Basic motion decomposition (paper 3.5): a chain of m sparse-coding decompositions, each of
// the residual the previous ones left, each with its own sparsity:
//   X = sum_i W_i C_i + residual.
#include <Eigen/Core>
#include <vector>

#include "engine/decompose/decomposition.h"
#include "engine/base/job_control.h"

namespace mostyle {

struct BasicMotionOptions {
  int components = 10;  // k of every level, 1 <= k <= 3N
  // One sparsity f_i in (0, 1] per level, applied as DecompositionOptions::sparsity; the chain
  // has m = sparsities.size() >= 1 levels.
  std::vector<double> sparsities = {0.1, 0.1, 0.1};
  int max_iterations = 100;          // per level, as DecompositionOptions
  double tolerance = 1e-6;           // per level, as DecompositionOptions
  int sparse_coding_iterations = 5;  // per level, as DecompositionOptions

  // Throws InputError when the chain is empty or any level's options are invalid for x.
  void Validate(const Eigen::MatrixXd& x) const;
  // The options of level i (0-based).
  DecompositionOptions Level(int i) const;
};

struct BasicMotions {
  // Level i's decomposition of the residual left by levels 0..i-1 (level 0 decomposes X); its
  // objective and rmse are relative to that residual. X_fi = levels[i].weights * components.
  std::vector<Decomposition> levels;
  Eigen::MatrixXd residual;  // X - sum_i W_i C_i: frames x 3N, X's units
  double elapsed_ms = 0.0;
};

// Decomposes x (frames x 3N, normalized) into options.sparsities.size() basic motions.
// sum_i W_i C_i + residual reproduces x up to rounding: the residual is x minus each level's
// product in turn.
// control (may be null): cancel checked once per round of every level, progress 0..1 over the
// whole chain. Throws InputError from options.Validate(x), Cancelled on cancel.
// Cost: m times decompose() on x's size.
BasicMotions decompose_basic_motions(const Eigen::MatrixXd& x,
                                     const BasicMotionOptions& options = {},
                                     JobControl* control = nullptr);

}  // namespace mostyle
