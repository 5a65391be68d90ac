#include "engine/post/speed_limit.h"

#include <algorithm>
#include <cmath>

namespace mostyle {

int limit_joint_speed(Eigen::MatrixXd& world, double fps, double limit, SpeedLimitScratch& scratch) {
  const Eigen::Index frames = world.rows(), joints = world.cols() / 3;
  if (!(limit > 0.0) || !(fps > 0.0) || frames < 3 || joints < 2) return 0;
  const double per_step = limit / fps;
  const Eigen::Index spread = std::max<Eigen::Index>(1, std::lround(kSpeedLimitSpreadSeconds * fps));
  // What each step may move relative to the root: the limit less the root's own step.
  std::vector<double>& allowed = scratch.allowed;
  allowed.resize(static_cast<size_t>(frames - 1));
  for (Eigen::Index t = 0; t + 1 < frames; ++t)
    allowed[static_cast<size_t>(t)] =
        std::max(0.0, per_step - (world.block<1, 3>(t + 1, 0) - world.block<1, 3>(t, 0)).norm());
  int changed = 0;
  Eigen::MatrixXd& steps = scratch.steps;
  steps.resize(frames - 1, 3);
  for (Eigen::Index j = 1; j < joints; ++j) {
    // The joint's steps relative to the root.
    for (Eigen::Index t = 0; t + 1 < frames; ++t)
      steps.row(t) = (world.block<1, 3>(t + 1, 3 * j) - world.block<1, 3>(t + 1, 0)) -
                     (world.block<1, 3>(t, 3 * j) - world.block<1, 3>(t, 0));
    bool any = false;
    for (Eigen::Index t = 0; t + 1 < frames; ++t) {
      const double size = steps.row(t).norm();
      const double cap = allowed[static_cast<size_t>(t)];
      if (size <= cap || size <= 0.0) continue;
      // The excess, spread over the nearest steps that have room for it, widening as needed.
      Eigen::RowVector3d excess = steps.row(t) * (1.0 - cap / size);
      steps.row(t) -= excess;
      for (Eigen::Index w = 1; w <= spread && excess.norm() > 0.0; ++w) {
        const Eigen::Index lo = std::max<Eigen::Index>(0, t - w), hi = std::min<Eigen::Index>(frames - 2, t + w);
        const double share = 1.0 / double(hi - lo);  // the window's steps but t
        const Eigen::RowVector3d part = excess * share;
        bool fits = true;
        for (Eigen::Index k = lo; k <= hi && fits; ++k)
          if (k != t) fits = (steps.row(k) + part).norm() <= allowed[static_cast<size_t>(k)];
        if (!fits && w < spread) continue;
        for (Eigen::Index k = lo; k <= hi; ++k)
          if (k != t) steps.row(k) += part;
        excess.setZero();
      }
      any = true;
      ++changed;
    }
    if (!any) continue;
    // Integrated again from the first frame, relative to the root.
    Eigen::RowVector3d at = world.block<1, 3>(0, 3 * j) - world.block<1, 3>(0, 0);
    for (Eigen::Index t = 0; t + 1 < frames; ++t) {
      at += steps.row(t);
      world.block<1, 3>(t + 1, 3 * j) = world.block<1, 3>(t + 1, 0) + at;
    }
  }
  return changed;
}

int limit_joint_speed_keeping_bones(Eigen::MatrixXd& world, double fps, double limit, const std::vector<int>& parents,
                                    const std::vector<double>& lengths, const LimbLengthOptions& limbs,
                                    SpeedLimitScratch& scratch) {
  int passes = 0;
  for (; passes < kSpeedLimitPasses; ++passes) {
    if (limit_joint_speed(world, fps, limit, scratch) == 0) break;
    apply_limb_lengths(world, parents, lengths, limbs);
  }
  return passes;
}

}  // namespace mostyle
