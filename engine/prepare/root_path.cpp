#include "engine/prepare/root_path.h"

#include <cmath>
#include <string>

#include "engine/base/error.h"

namespace mostyle {

Eigen::MatrixXd root_steps(const Eigen::MatrixXd& ground, const Eigen::VectorXd& heading) {
  const Eigen::Index frames = ground.rows();
  Eigen::MatrixXd steps = Eigen::MatrixXd::Zero(frames, 3);
  for (Eigen::Index t = 0; t + 1 < frames; ++t) {
    const double dx = ground(t + 1, 0) - ground(t, 0), dz = ground(t + 1, 1) - ground(t, 1);
    const double c = std::cos(heading[t]), s = std::sin(heading[t]);
    steps(t, 0) = c * dx - s * dz;
    steps(t, 1) = s * dx + c * dz;
    steps(t, 2) = heading[t + 1] - heading[t];
  }
  return steps;
}

Eigen::MatrixXd root_steps(const CanonicalMotion& motion) {
  return root_steps(motion.ground, motion.heading);
}

void integrate_root(const Eigen::MatrixXd& steps, const Eigen::Vector2d& start_ground,
                    double start_heading, Eigen::MatrixXd* ground, Eigen::VectorXd* heading) {
  const Eigen::Index frames = steps.rows();
  ground->resize(frames, 2);
  heading->resize(frames);
  if (frames == 0) return;
  (*ground)(0, 0) = start_ground.x();
  (*ground)(0, 1) = start_ground.y();
  (*heading)[0] = start_heading;
  for (Eigen::Index t = 0; t + 1 < frames; ++t) {
    const double c = std::cos((*heading)[t]), s = std::sin((*heading)[t]);
    // R_y(h) (vx, vz): x = c vx + s vz, z = -s vx + c vz.
    (*ground)(t + 1, 0) = (*ground)(t, 0) + c * steps(t, 0) + s * steps(t, 1);
    (*ground)(t + 1, 1) = (*ground)(t, 1) - s * steps(t, 0) + c * steps(t, 1);
    (*heading)[t + 1] = (*heading)[t] + steps(t, 2);
  }
}

Eigen::MatrixXd limit_warped_steps(const Eigen::MatrixXd& steps, const Eigen::VectorXd& warp,
                                   double max_speedup) {
  if (steps.cols() != 3 || steps.rows() != warp.size())
    throw InputError("cannot limit warped root steps: " + std::to_string(steps.rows()) + " x " +
                     std::to_string(steps.cols()) + " steps for a warp of " + std::to_string(warp.size()) +
                     " frames (expected F x 3 and F)");
  Eigen::MatrixXd out = steps;
  for (Eigen::Index t = 0; t + 1 < steps.rows(); ++t) {
    const double skipped = warp[t + 1] - warp[t];
    if (skipped > max_speedup) out.block<1, 2>(t, 0) *= max_speedup / skipped;
  }
  return out;
}

Eigen::MatrixXd match_turns(const Eigen::MatrixXd& steps_b, const Eigen::MatrixXd& steps_a) {
  if (steps_a.rows() != steps_b.rows() || steps_a.cols() != 3 || steps_b.cols() != 3)
    throw InputError("cannot match turns: root steps of " + std::to_string(steps_a.rows()) + " x " +
                     std::to_string(steps_a.cols()) + " and " + std::to_string(steps_b.rows()) + " x " +
                     std::to_string(steps_b.cols()) + " (expected F x 3 both)");
  Eigen::MatrixXd out = steps_b;
  // D = H_B - H_A, both integrated from 0; `whole` turns are taken off B's heading so that
  // |D - 2 pi whole| stays within pi + hysteresis. Changing `whole` at frame t + 1 moves B's turn
  // of step t by the same number of whole turns, which integrate_root cannot tell apart.
  double difference = 0.0;
  double whole = 0.0;
  for (Eigen::Index t = 0; t + 1 < steps_b.rows(); ++t) {
    difference += steps_b(t, 2) - steps_a(t, 2);
    const double wrapped = difference - 2 * M_PI * whole;
    if (std::abs(wrapped) > M_PI + kTurnHysteresis) {
      const double next = std::round(difference / (2 * M_PI));
      out(t, 2) -= 2 * M_PI * (next - whole);
      whole = next;
    }
  }
  return out;
}

}  // namespace mostyle
