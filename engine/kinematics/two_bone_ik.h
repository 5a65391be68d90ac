#pragma once
// Two-bone IK on joint positions: a chain of three joints (a leg's hip, knee and ankle) whose end
// is moved to a target, both bones keeping their lengths. The foot lock, the swing clearance, the
// stride warp and the live styler move legs with it.
#include <Eigen/Core>

namespace mostyle {

// A bend (the middle joint off the line from the first joint to the target) shorter than this
// fraction of the chain's length has no direction of its own.
constexpr double kStraightChain = 1e-4;

// One two-bone IK solve, exposed for tests: hip, knee, ankle are the chain's joints, `target`
// where the ankle should go. Returns the new knee and ankle (hip unchanged); thigh |knee - hip|
// and shin |ankle - knee| keep their lengths. `bend_fallback` is used as the knee's bend
// direction when the leg is straight (knee on the hip-target line).
void two_bone_ik(const Eigen::Vector3d& hip, const Eigen::Vector3d& knee, const Eigen::Vector3d& ankle,
                 const Eigen::Vector3d& target, const Eigen::Vector3d& bend_fallback,
                 Eigen::Vector3d* new_knee, Eigen::Vector3d* new_ankle);
// The same with the bend direction taken from `pole` (its part perpendicular to hip-target)
// instead of from the knee; bend_fallback where that part vanishes.
void two_bone_ik_pole(const Eigen::Vector3d& hip, const Eigen::Vector3d& knee, const Eigen::Vector3d& ankle,
                      const Eigen::Vector3d& target, const Eigen::Vector3d& pole, const Eigen::Vector3d& bend_fallback,
                      Eigen::Vector3d* new_knee, Eigen::Vector3d* new_ankle);

}  // namespace mostyle
