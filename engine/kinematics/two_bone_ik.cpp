#include "engine/kinematics/two_bone_ik.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace mostyle {
namespace {

// Any unit vector perpendicular to n (unit).
Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d axis = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(axis).normalized();
}

}  // namespace

bool TwoBoneIkJob::Validate() const {
  return start.allFinite() && mid.allFinite() && end.allFinite() && target.allFinite() && pole.allFinite() &&
         bend_fallback.allFinite();
}

TwoBoneIkResult TwoBoneIkJob::Run() const {
  TwoBoneIkResult out{mid, end, false};
  if (!Validate()) return out;
  const double upper = (mid - start).norm();
  const double lower = (end - mid).norm();
  const Eigen::Vector3d to_target = target - start;
  const double distance = to_target.norm();
  if (!(distance > kStraightChain * (upper + lower))) return out;  // target on the start: no direction
  const Eigen::Vector3d n = to_target / distance;
  // Law of cosines in the plane of start, target and the bend direction.
  const double margin = kChainMargin * (upper + lower);
  const double reach = std::clamp(distance, std::abs(upper - lower) + margin, upper + lower - margin);
  Eigen::Vector3d bend = pole - n * n.dot(pole);
  if (bend.norm() <= kStraightChain * (upper + lower)) bend = bend_fallback - n * n.dot(bend_fallback);
  bend = bend.norm() > 0 ? Eigen::Vector3d(bend.normalized()) : any_perpendicular(n);
  const double along = (upper * upper - lower * lower + reach * reach) / (2.0 * reach);
  const double across = std::sqrt(std::max(0.0, upper * upper - along * along));
  out.mid = start + n * along + bend * across;
  out.end = start + n * reach;
  out.reached = reach == distance;
  return out;
}

}  // namespace mostyle
