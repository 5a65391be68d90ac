#include "engine/post/swing_clearance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "engine/base/error.h"
#include "engine/kinematics/ease.h"
#include "engine/kinematics/joint_rows.h"
#include "engine/kinematics/two_bone_ik.h"
#include "engine/measure/planted_feet.h"
#include "engine/post/leg_move.h"

namespace mostyle {
namespace {

// A lift of this many leg lengths (or more) bends the knee wholly forwards (raise_leg).
constexpr double kKneeFullLift = 0.02;
// How far forwards a lifted knee is biased, leg lengths: enough to pick a side where the leg is
// straight, too little to turn a bent knee's plane.
constexpr double kKneeForwardBias = 0.02;
// Passes of lifting against the floor the last one left (lift_swinging_feet).
constexpr int kSwingPasses = 4;

// need (F) eased into lift (F): on each frame the largest of its neighbours' needs within `ramp`
// frames, each scaled by smoothstep of how near it is (1 on the frame itself). O(F x ramp).
void ease_lift(const Eigen::VectorXd& need, int ramp, Eigen::VectorXd& lift) {
  const Eigen::Index frames = need.size();
  lift.setZero(frames);
  for (Eigen::Index t = 0; t < frames; ++t) {
    if (!(need[t] > 0.0)) continue;
    for (Eigen::Index d = -ramp; d <= ramp; ++d) {
      const Eigen::Index u = t + d;
      if (u < 0 || u >= frames) continue;
      const double taper = smoothstep(1.0 - static_cast<double>(std::abs(d)) / (ramp + 1));
      lift[u] = std::max(lift[u], taper * need[t]);
    }
  }
}

// The leg's ankle raised by lift[t] on every frame with a lift, the toe moved with it. The knee
// bends in its own plane (the least change to the pose), but forwards, the way the body faces
// (the hips' left-right line turned a quarter about the vertical): a knee a mix leaves nearly
// straight, or bent a little backwards, would fold backwards or flip its bend from one frame to
// the next as the lift bends it. Both corrections grow with the lift from none, so a lift
// easing in bends the knee from where it was. O(F).
void raise_leg(Eigen::MatrixXd& world, const LegColumns& leg, const std::array<LegColumns, 2>& legs,
               double leg_length, const Eigen::VectorXd& lift) {
  for (Eigen::Index t = 0; t < world.rows(); ++t) {
    if (!(lift[t] > 0.0)) continue;
    const Eigen::Vector3d hip = joint_at(world, t, leg.hip), knee = joint_at(world, t, leg.knee);
    const Eigen::Vector3d ankle = joint_at(world, t, leg.ankle);
    Eigen::Vector3d facing = Eigen::Vector3d::Zero();  // none with one hip: the knee's own plane
    if (legs[0].hip >= 0 && legs[1].hip >= 0) {
      const Eigen::Vector3d across = joint_at(world, t, legs[0].hip) - joint_at(world, t, legs[1].hip);
      facing = Eigen::Vector3d(-across.z(), 0.0, across.x());
      if (facing.norm() > 0) facing.normalize();
    }
    const Eigen::Vector3d line = ankle - hip;
    Eigen::Vector3d pole = knee - hip;
    if (line.squaredNorm() > 0) pole -= line * (line.dot(pole) / line.squaredNorm());
    const double moving = std::clamp(lift[t] / (kKneeFullLift * leg_length), 0.0, 1.0);
    const double back = pole.dot(facing);
    if (back < 0.0) pole -= moving * back * facing;
    pole += moving * kKneeForwardBias * leg_length * facing;
    TwoBoneIkJob ik;
    ik.start = hip;
    ik.mid = knee;
    ik.end = ankle;
    ik.target = ankle + Eigen::Vector3d(0.0, lift[t], 0.0);
    ik.pole = pole;
    ik.bend_fallback = facing;
    place_leg(world, t, leg, ik.Run());
  }
}

}  // namespace

double lift_swinging_feet(Eigen::MatrixXd& world, const FootRig& rig, const Eigen::MatrixXd& air,
                          SwingClearanceScratch& s) {
  const Eigen::Index frames = world.rows();
  if (air.rows() != frames || air.cols() != kFootJoints)
    throw InputError("swing clearance: expected the feet in the air as " + std::to_string(frames) + " x " +
                     std::to_string(kFootJoints) + ", found " + std::to_string(air.rows()) + " x " +
                     std::to_string(air.cols()));
  const double band = kPlantedHeightFraction * rig.body_height, clear = kSwingClearanceBands * band;
  const int ramp = std::max(1, static_cast<int>(std::lround(kSwingEaseSeconds * rig.fps)));
  const std::array<int, kFootJoints> columns = foot_joint_columns(rig);
  s.total.setZero(frames, 2);
  // A joint's floor is a low percentile of its own heights: where the frames lifted were its
  // lowest (a mix that sinks a swinging foot below the floor), the floor rises with them, and the
  // lifted frames are in the band of the new floor. Lifted again against it, a few passes settle
  // on the floor the planted frames give.
  for (int pass = 0; pass < kSwingPasses; ++pass) {
    std::array<double, kFootJoints> floors;
    planted_frames(world, rig, s.planted, s.heights, &floors);
    bool lifted = false;
    for (int side = 0; side < 2; ++side) {
      const LegColumns& leg = rig.legs[static_cast<size_t>(side)];
      if (!leg.usable()) continue;
      s.need.setZero(frames);
      for (int j = 2 * side; j < 2 * side + 2; ++j) {
        const int c = columns[static_cast<size_t>(j)];
        if (c < 0) continue;
        for (Eigen::Index t = 0; t < frames; ++t) {
          const double above = world(t, 3 * c + 1) - floors[static_cast<size_t>(j)];
          if (air(t, j) > 0.5 && above <= band) s.need[t] = std::max(s.need[t], clear - above);
        }
      }
      if (!(s.need.maxCoeff() > 0.0)) continue;
      ease_lift(s.need, ramp, s.lift);
      raise_leg(world, leg, rig.legs, rig.leg_length, s.lift);
      s.total.col(side) += s.lift;
      lifted = true;
    }
    if (!lifted) break;
  }
  const double largest = frames > 0 ? s.total.maxCoeff() : 0.0;
  return largest;
}

}  // namespace mostyle
