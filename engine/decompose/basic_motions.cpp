#include "engine/decompose/basic_motions.h"

#include <chrono>
#include <string>

#include "engine/base/clock.h"
#include "engine/base/error.h"

namespace mostyle {

void BasicMotionOptions::Validate(const Eigen::MatrixXd& x) const {
  if (sparsities.empty()) {
    throw InputError("basic motions: the chain needs at least one level (one sparsity).");
  }
  for (size_t i = 0; i < sparsities.size(); ++i) {
    try {
      Level(static_cast<int>(i)).Validate(x);
    } catch (const InputError& e) {
      throw InputError("basic motions, level " + std::to_string(i + 1) + ": " + e.what());
    }
  }
}

DecompositionOptions BasicMotionOptions::Level(int i) const {
  DecompositionOptions level;
  level.components = components;
  level.sparsity = sparsities.at(static_cast<size_t>(i));
  level.max_iterations = max_iterations;
  level.tolerance = tolerance;
  level.sparse_coding_iterations = sparse_coding_iterations;
  return level;
}

BasicMotions decompose_basic_motions(const Eigen::MatrixXd& x, const BasicMotionOptions& options,
                                     JobControl* control) {
  const auto start = std::chrono::steady_clock::now();
  options.Validate(x);
  const int levels = static_cast<int>(options.sparsities.size());

  // Paper 3.5: X_fi = W_fi C_fi is extracted with sparsity f_i and removed, X <- X - X_fi, and
  // the next level works on what is left.
  BasicMotions result;
  result.levels.reserve(static_cast<size_t>(levels));
  result.residual = x;
  for (int i = 0; i < levels; ++i) {
    const float begin = static_cast<float>(i) / static_cast<float>(levels);
    const float end = static_cast<float>(i + 1) / static_cast<float>(levels);
    result.levels.push_back(
        detail::decompose_part(result.residual, options.Level(i), control, begin, end));
    const Decomposition& level = result.levels.back();
    result.residual.noalias() -= level.weights * level.components;
  }
  result.elapsed_ms = ms_since(start);
  return result;
}

}  // namespace mostyle
