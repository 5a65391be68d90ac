#include "engine/kinematics/two_bone_ik.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace mostyle {
namespace {

// Fraction of the leg's length the IK keeps away from full extension or folding.
constexpr double kExtensionMargin = 1e-9;

// Any unit vector perpendicular to n (unit).
Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d axis = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(axis).normalized();
}

}  // namespace

void two_bone_ik(const Eigen::Vector3d& hip, const Eigen::Vector3d& knee, const Eigen::Vector3d& ankle,
                 const Eigen::Vector3d& target, const Eigen::Vector3d& bend_fallback,
                 Eigen::Vector3d* new_knee, Eigen::Vector3d* new_ankle) {
  two_bone_ik_pole(hip, knee, ankle, target, knee - hip, bend_fallback, new_knee, new_ankle);
}

void two_bone_ik_pole(const Eigen::Vector3d& hip, const Eigen::Vector3d& knee, const Eigen::Vector3d& ankle,
                      const Eigen::Vector3d& target, const Eigen::Vector3d& pole, const Eigen::Vector3d& bend_fallback,
                      Eigen::Vector3d* new_knee, Eigen::Vector3d* new_ankle) {
  const double thigh = (knee - hip).norm();
  const double shin = (ankle - knee).norm();
  const Eigen::Vector3d to_target = target - hip;
  const double distance = to_target.norm();
  if (!(distance > kStraightChain * (thigh + shin))) {  // target on the hip: no direction to reach
    *new_knee = knee;
    *new_ankle = ankle;
    return;
  }
  const Eigen::Vector3d n = to_target / distance;
  // Law of cosines in the plane of hip, target and the knee's bend direction.
  // Short of full extension (and of full folding) by a hair: there the knee's distance from the
  // hip-target line is the square root of a difference that vanishes, so rounding in the input
  // would move the knee by the square root of rounding (1e-8 of the leg, not 1e-16).
  const double margin = kExtensionMargin * (thigh + shin);
  const double reach = std::clamp(distance, std::abs(thigh - shin) + margin, thigh + shin - margin);
  Eigen::Vector3d bend = pole - n * n.dot(pole);
  if (bend.norm() <= kStraightChain * (thigh + shin)) bend = bend_fallback - n * n.dot(bend_fallback);
  bend = bend.norm() > 0 ? Eigen::Vector3d(bend.normalized()) : any_perpendicular(n);
  const double along = (thigh * thigh - shin * shin + reach * reach) / (2.0 * reach);
  const double across = std::sqrt(std::max(0.0, thigh * thigh - along * along));
  *new_knee = hip + n * along + bend * across;
  *new_ankle = hip + n * reach;
}

}  // namespace mostyle
