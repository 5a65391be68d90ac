#include "engine/synthesize/synthesis.h"

#include <cmath>
#include <string>

#include "engine/base/error.h"

namespace mostyle {

namespace {

void require_finite_alpha(double alpha, const char* where) {
  if (!std::isfinite(alpha)) {
    throw InputError(std::string(where) + ": alpha must be a finite number, got " +
                     std::to_string(alpha) + ".");
  }
}

// out = (1 - alpha) a + alpha b in one pass; exactly a at alpha = 0 and b at alpha = 1.
void lerp(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double alpha, Eigen::MatrixXd& out) {
  out.resize(a.rows(), a.cols());
  out = (1.0 - alpha) * a + alpha * b;
}

}  // namespace

void synthesize_paper(const PaperSynthesis& p, double alpha, Eigen::MatrixXd& out) {
  require_finite_alpha(alpha, "paper synthesis");
  lerp(p.motion_a, p.motion_b, alpha, out);
}

Eigen::MatrixXd synthesize_paper(const PaperSynthesis& p, double alpha) {
  Eigen::MatrixXd out;
  synthesize_paper(p, alpha, out);
  return out;
}

void synthesize_basic_motions(const BasicMotionSynthesis& p, int swap, double alpha,
                              Eigen::MatrixXd& out) {
  const int levels = static_cast<int>(p.swap_delta.size());
  if (swap < 0 || swap >= levels) {
    throw InputError("basic motion synthesis: the swapped level must be between 1 and " +
                     std::to_string(levels) + ", got " + std::to_string(swap + 1) + ".");
  }
  require_finite_alpha(alpha, "basic motion synthesis");
  out.resize(p.motion_a.rows(), p.motion_a.cols());
  out = p.motion_a + alpha * p.swap_delta[static_cast<size_t>(swap)];
}

Eigen::MatrixXd synthesize_basic_motions(const BasicMotionSynthesis& p, int swap, double alpha) {
  Eigen::MatrixXd out;
  synthesize_basic_motions(p, swap, alpha, out);
  return out;
}

}  // namespace mostyle
