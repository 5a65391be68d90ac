#pragma once
// How fast a motion's fastest joint moves: the measure outputs are held to against their takes
// (no pops: a blend, mix or transfer moves no joint much faster than its fastest take does).
#include <Eigen/Core>
#include <vector>

namespace mostyle {

constexpr double kFastestJointPercentile = 0.999;  // of the frame steps: one bad step in a thousand is left out

// The kFastestJointPercentile percentile (nearest rank) over frame steps t -> t + 1 of the
// fastest joint's speed on that step, file units per second. world: F x 3M at fps. 0 with fewer
// than two frames. O(F x M + F log F); allocates F values.
double fastest_joint_speed(const Eigen::MatrixXd& world, double fps);
// The same with its frame steps in `steps` (resized to F - 1): no allocation once sized.
double fastest_joint_speed(const Eigen::MatrixXd& world, double fps, std::vector<double>& steps);

}  // namespace mostyle
