#pragma once
// Retargeting: B's major-joint positions on A's bone lengths (A is the reference).
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

// The fixed shape of each joint group (a joint with several children: the pelvis with spine and
// hip joints, the chest with neck and shoulders) is a property of the skeleton, not of the
// motion. In place on B's positions (Fb x 3J): in each frame B's group is a rotation of B's mean
// group shape plus a deviation (a shrug, say); B's mean shape is swapped for A's (from world_a,
// Fa x 3J), the rotation and deviation kept, and each child's subtree moves with its child.
// A take given as its own B is left unchanged. Without it, a blend of a narrow-shouldered A
// with a wide-shouldered B has shoulders that A's skeleton cannot reach. O(frames x J).
void adopt_group_shapes(Eigen::MatrixXd& world_b, const Eigen::MatrixXd& world_a,
                        const std::vector<int>& parents);

}  // namespace mostyle
