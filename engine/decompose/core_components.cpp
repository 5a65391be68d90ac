#include "engine/decompose/core_components.h"

#include <Eigen/SVD>
#include <cmath>
#include <string>

#include "engine/base/error.h"

namespace mostyle {

namespace {

std::string shape(const Eigen::MatrixXd& m) {
  return std::to_string(m.rows()) + " x " + std::to_string(m.cols());
}

}  // namespace

CoreComponents core_components(const Eigen::MatrixXd& components) {
  if (components.rows() == 0 || components.rows() > components.cols()) {
    throw InputError("core components: need 1 <= k <= 3N components, got " + shape(components) +
                     ".");
  }
  if (!components.allFinite()) {
    throw InputError("core components: the components hold a NaN or infinite value.");
  }
  // Paper 3.6, "Components SVD": C = (U S) V^T = K V^T. With k <= 3N the thin SVD has U k x k,
  // S k and V 3N x k, so K is square and V^T maps it back to channels.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(components, Eigen::ComputeThinU | Eigen::ComputeThinV);
  if (svd.info() != Eigen::Success) {
    throw InputError("core components: the SVD of the components did not converge.");
  }
  CoreComponents result;
  result.core = svd.matrixU() * svd.singularValues().asDiagonal();
  result.basis = svd.matrixV();
  // Each singular pair (u_i, v_i) is only defined up to a common sign. K_A V_A^T does not care,
  // but the paper's K_B V_A^T does, so fix the sign by a rule independent of the SVD routine.
  for (Eigen::Index i = 0; i < result.basis.cols(); ++i) {
    Eigen::Index largest = 0;
    result.basis.col(i).cwiseAbs().maxCoeff(&largest);
    if (result.basis(largest, i) < 0.0) {
      result.basis.col(i) *= -1.0;
      result.core.col(i) *= -1.0;
    }
  }
  return result;
}

PaperSynthesis prepare_paper_synthesis(const Eigen::MatrixXd& weights_a, const CoreComponents& a,
                                       const CoreComponents& b) {
  if (a.core.rows() != a.core.cols() || weights_a.cols() != a.core.rows() ||
      a.basis.cols() != a.core.cols()) {
    throw InputError("paper synthesis: A's weights (" + shape(weights_a) + "), core (" +
                     shape(a.core) + ") and basis (" + shape(a.basis) + ") do not fit.");
  }
  if (b.core.rows() != a.core.rows() || b.core.cols() != a.core.cols() ||
      b.basis.rows() != a.basis.rows()) {
    throw InputError("paper synthesis: B's core (" + shape(b.core) + ", basis " +
                     shape(b.basis) + ") must have A's k and channels (" + shape(a.core) +
                     ", basis " + shape(a.basis) + ").");
  }
  // Paper 3.6, "Components synthesis": X_syn = W_A ((1 - alpha) K_A + alpha K_B) V_A^T
  //   = (1 - alpha) W_A K_A V_A^T + alpha W_A K_B V_A^T,
  // so both ends are fixed and a slider move only blends them.
  PaperSynthesis p;
  const Eigen::MatrixXd mix_a = a.core * a.basis.transpose();  // k x 3N
  const Eigen::MatrixXd mix_b = b.core * a.basis.transpose();  // k x 3N
  p.motion_a.noalias() = weights_a * mix_a;
  p.motion_b.noalias() = weights_a * mix_b;
  return p;
}

BasicMotionSynthesis prepare_basic_motion_synthesis(const BasicMotions& a, const BasicMotions& b) {
  const size_t levels = a.levels.size();
  if (levels == 0 || b.levels.size() != levels) {
    throw InputError("basic motion synthesis: both takes need the same number of basic motions "
                     "(at least 1), got " + std::to_string(levels) + " and " +
                     std::to_string(b.levels.size()) + ".");
  }
  const Eigen::Index frames = a.levels[0].weights.rows();
  const Eigen::Index k = a.levels[0].components.rows();
  const Eigen::Index channels = a.levels[0].components.cols();
  for (size_t i = 0; i < levels; ++i) {
    const Decomposition& la = a.levels[i];
    const Decomposition& lb = b.levels[i];
    if (la.weights.rows() != frames || la.weights.cols() != k || la.components.rows() != k ||
        la.components.cols() != channels || lb.components.rows() != k ||
        lb.components.cols() != channels) {
      throw InputError("basic motion synthesis: level " + std::to_string(i + 1) +
                       " does not match level 1's shapes (weights " + shape(la.weights) +
                       ", components A " + shape(la.components) + ", components B " +
                       shape(lb.components) + ").");
    }
  }
  // Paper 3.6, "Basic motion synthesis": X_syn = sum_i W^A_i K^A_i V^A_i^T with K^A_s -> K^B_s.
  // Blending level s's core by alpha adds alpha W^A_s (K^B_s - K^A_s) V^A_s^T to A's sum.
  BasicMotionSynthesis p;
  p.motion_a = Eigen::MatrixXd::Zero(frames, channels);
  p.swap_delta.resize(levels);
  for (size_t i = 0; i < levels; ++i) {
    const CoreComponents core_a = core_components(a.levels[i].components);
    const CoreComponents core_b = core_components(b.levels[i].components);
    const Eigen::MatrixXd basis_t = core_a.basis.transpose();
    const Eigen::MatrixXd mix_a = core_a.core * basis_t;                  // k x 3N
    const Eigen::MatrixXd delta = (core_b.core - core_a.core) * basis_t;  // k x 3N
    p.motion_a.noalias() += a.levels[i].weights * mix_a;
    p.swap_delta[i].noalias() = a.levels[i].weights * delta;
  }
  return p;
}

}  // namespace mostyle
