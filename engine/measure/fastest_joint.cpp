#include "engine/measure/fastest_joint.h"

#include <algorithm>
#include <vector>

namespace mostyle {

double fastest_joint_speed(const Eigen::MatrixXd& world, double fps) {
  std::vector<double> steps;
  return fastest_joint_speed(world, fps, steps);
}

double fastest_joint_speed(const Eigen::MatrixXd& world, double fps, std::vector<double>& steps) {
  if (world.rows() < 2) return 0.0;
  steps.assign(static_cast<size_t>(world.rows() - 1), 0.0);
  for (Eigen::Index t = 0; t + 1 < world.rows(); ++t)
    for (Eigen::Index c = 0; c + 2 < world.cols(); c += 3)
      steps[static_cast<size_t>(t)] =
          std::max(steps[static_cast<size_t>(t)], (world.block<1, 3>(t + 1, c) - world.block<1, 3>(t, c)).norm());
  const size_t k = std::min(steps.size() - 1, static_cast<size_t>(kFastestJointPercentile * static_cast<double>(steps.size())));
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(k), steps.end());
  return steps[k] * fps;
}

}  // namespace mostyle
