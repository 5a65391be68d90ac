#pragma once
// Retargeting (DESIGN.md 3): B's major-joint positions on A's bone lengths.
#include <Eigen/Core>
#include <vector>

namespace mostyle {

// Sum of thigh and shin lengths averaged over both legs. lengths: per joint (bone_lengths());
// columns: the joints' indices of (left hip, left knee, left ankle, right hip, right knee,
// right ankle). File units.
double leg_length(const std::vector<double>& lengths, const int (&leg_joints)[6]);

// B's positions (F x 3J) scaled by leg_a / leg_b (so stride and root height follow A's legs),
// then each bone set to A's length from the root outward, keeping B's bone directions.
// parents: per joint, parents first. Throws InputError on a zero leg length.
Eigen::MatrixXd retarget_positions(const Eigen::MatrixXd& world_b, const std::vector<int>& parents,
                                   const std::vector<double>& lengths_a, double leg_a, double leg_b);

}  // namespace mostyle
