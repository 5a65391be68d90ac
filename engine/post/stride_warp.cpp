#include "engine/post/stride_warp.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/base/error.h"
#include "engine/kinematics/joint_rows.h"
#include "engine/kinematics/two_bone_ik.h"

namespace mostyle {
namespace {

// (x, z) of p through the frame's map (row k of map), its height kept.
Eigen::Vector3d mapped(const Eigen::MatrixXd& map, Eigen::Index k, const Eigen::Vector3d& p) {
  return Eigen::Vector3d(map(k, 0) * p.x() + map(k, 1) * p.z(), p.y(), map(k, 2) * p.x() + map(k, 3) * p.z());
}

// How far the leg reaches from its hip: thigh and shin, short of straight by kStrideReachMargin
// of them (a leg held straight has no knee bend left for the IK to turn).
double reach(const Eigen::MatrixXd& local, Eigen::Index k, const LegColumns& leg) {
  const Eigen::Vector3d hip = joint_at(local, k, leg.hip), knee = joint_at(local, k, leg.knee);
  const Eigen::Vector3d ankle = joint_at(local, k, leg.ankle);
  return (1.0 - kStrideReachMargin) * ((knee - hip).norm() + (ankle - knee).norm());
}

// The target, or where the way from the ankle to it leaves the leg's reach: a stride stretched
// past what the leg reaches stops there with the foot at its height (two-bone IK would otherwise
// keep the target's direction and lift the foot off the floor). An ankle already beyond the reach
// (a leg nearly straight at a heel strike) goes to a target no further from the hip than itself,
// and stays where the target is further.
Eigen::Vector3d within_reach(const Eigen::Vector3d& hip, const Eigen::Vector3d& ankle, const Eigen::Vector3d& target,
                             double reach) {
  const double from_hip = (ankle - hip).norm();
  if ((target - hip).norm() <= std::max(reach, from_hip)) return target;
  if (from_hip >= reach) return ankle;
  // |ankle + t (target - ankle) - hip| = reach for t in (0, 1): the root of a quadratic.
  const Eigen::Vector3d d = target - ankle, a = ankle - hip;
  const double qa = d.squaredNorm(), qb = 2.0 * a.dot(d), qc = a.squaredNorm() - reach * reach;
  const double t = (-qb + std::sqrt(std::max(0.0, qb * qb - 4.0 * qa * qc))) / (2.0 * qa);
  return ankle + std::clamp(t, 0.0, 1.0) * d;
}

bool is_identity(const Eigen::MatrixXd& map, Eigen::Index k) {
  return map(k, 0) == 1.0 && map(k, 1) == 0.0 && map(k, 2) == 0.0 && map(k, 3) == 1.0;
}

}  // namespace

void warp_strides(Eigen::MatrixXd& local, const Eigen::MatrixXd& map, const FootRig& rig) {
  if (map.rows() != local.rows() || map.cols() != 4)
    throw InputError("stride warp: expected a map of " + std::to_string(local.rows()) + " x 4, found " +
                     std::to_string(map.rows()) + " x " + std::to_string(map.cols()));
  const Eigen::Vector3d forwards(0.0, 0.0, 1.0);  // the body frame's: knees bend the way it faces
  for (Eigen::Index k = 0; k < local.rows(); ++k) {
    if (is_identity(map, k)) continue;
    for (const LegColumns& leg : rig.legs) {
      if (!leg.usable()) continue;
      const Eigen::Vector3d hip = joint_at(local, k, leg.hip), knee = joint_at(local, k, leg.knee);
      const Eigen::Vector3d ankle = joint_at(local, k, leg.ankle);
      const Eigen::Vector3d target = within_reach(hip, ankle, mapped(map, k, ankle), reach(local, k, leg));
      TwoBoneIkJob ik;
      ik.start = hip;
      ik.mid = knee;
      ik.end = ankle;
      ik.target = target;
      ik.pole = knee - hip;  // the knee's own bend
      ik.bend_fallback = forwards;
      const TwoBoneIkResult stepped = ik.Run();
      const Eigen::Vector3d& new_knee = stepped.mid;
      const Eigen::Vector3d& new_ankle = stepped.end;
      if (leg.toe >= 0) {
        // The foot keeps its length and its pitch (the toe's drop below the ankle): only the way
        // it points across the floor follows the map. Mapped whole, a foot shortened along the
        // way and stretched back to its length would tip its toe into the floor.
        const Eigen::Vector3d foot = joint_at(local, k, leg.toe) - ankle;
        const Eigen::Vector2d flat(foot.x(), foot.z());
        Eigen::Vector2d way(map(k, 0) * flat.x() + map(k, 1) * flat.y(), map(k, 2) * flat.x() + map(k, 3) * flat.y());
        way = way.norm() > 0.0 ? Eigen::Vector2d(way * (flat.norm() / way.norm())) : flat;
        set_joint(local, k, leg.toe, new_ankle + Eigen::Vector3d(way.x(), foot.y(), way.y()));
      }
      set_joint(local, k, leg.knee, new_knee);
      set_joint(local, k, leg.ankle, new_ankle);
    }
  }
}

}  // namespace mostyle
