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

// The leg's ankle raised by lift[t] (lowered where it is negative) on every frame with a lift,
// the toe moved with it. The knee bends in its own plane (the least change to the pose), but
// forwards, the way the body faces (the hips' left-right line turned a quarter about the
// vertical): a knee a mix leaves nearly straight, or bent a little backwards, would fold
// backwards or flip its bend from one frame to the next as the lift bends it. Both corrections grow with the lift from none, so a lift
// easing in bends the knee from where it was. O(F).
void raise_leg(Eigen::MatrixXd& world, const LegColumns& leg, const std::array<LegColumns, 2>& legs,
               double leg_length, const Eigen::VectorXd& lift) {
  for (Eigen::Index t = 0; t < world.rows(); ++t) {
    if (lift[t] == 0.0 || !std::isfinite(lift[t])) continue;
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
    const double moving = std::clamp(std::abs(lift[t]) / (kKneeFullLift * leg_length), 0.0, 1.0);
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

namespace {

// For one foot joint: how much of its settling each frame takes (weight, F: 1 where the takes hold
// it and the output has it in the planted band, smoothstep over `ramp` frames to 0 beyond) and
// from which such frame (from, F; -1: none), the nearest. A foot the output swings where the
// takes' is down is not brought down into the band: it would move at swing speed there, a planted
// foot sliding. O(F x ramp).
void nearest_held(const Eigen::MatrixXd& held, const Eigen::MatrixXd& planted, int j, int ramp, Eigen::VectorXd& weight,
                  Eigen::VectorXi& from) {
  const Eigen::Index frames = held.rows();
  auto is_held = [&](Eigen::Index t) { return held(t, j) > 0.5 && planted(t, j) > 0.5; };
  weight.setZero(frames);
  from.setConstant(frames, -1);
  for (Eigen::Index t = 0; t < frames; ++t) {
    for (Eigen::Index d = 0; d <= ramp; ++d) {
      const Eigen::Index at = t - d >= 0 && is_held(t - d) ? t - d : t + d < frames && is_held(t + d) ? t + d : -1;
      if (at < 0) continue;
      weight[t] = smoothstep(1.0 - static_cast<double>(d) / (ramp + 1));
      from[t] = static_cast<int>(at);
      break;
    }
  }
}

}  // namespace

double settle_held_feet(Eigen::MatrixXd& world, const FootRig& rig, const Eigen::MatrixXd& heights,
                        const Eigen::MatrixXd& held, SwingClearanceScratch& s) {
  const Eigen::Index frames = world.rows();
  if (heights.rows() != frames || heights.cols() != kFootJoints || held.rows() != frames || held.cols() != kFootJoints)
    throw InputError("planted feet's heights: expected the takes' feet as " + std::to_string(frames) + " x " +
                     std::to_string(kFootJoints));
  const double band = kPlantedHeightFraction * rig.body_height;
  const int ramp = std::max(1, static_cast<int>(std::lround(kSwingEaseSeconds * rig.fps)));
  const std::array<int, kFootJoints> columns = foot_joint_columns(rig);
  std::array<double, kFootJoints> floors;
  planted_frames(world, rig, s.planted, s.heights, &floors);
  double largest = 0.0;
  Eigen::VectorXd& weight = s.weight;
  Eigen::VectorXi& from = s.from;
  for (int side = 0; side < 2; ++side) {
    const LegColumns& leg = rig.legs[static_cast<size_t>(side)];
    if (!leg.usable()) continue;
    const int ja = 2 * side, jt = 2 * side + 1;
    const int ca = columns[static_cast<size_t>(ja)], ct = columns[static_cast<size_t>(jt)];
    if (ca != leg.ankle) continue;
    // The ankle first, the leg bent to it (the toe moved with it)...
    nearest_held(held, s.planted, ja, ramp, weight, from);
    s.lift.setZero(frames);
    for (Eigen::Index t = 0; t < frames; ++t) {
      if (from[t] < 0) continue;
      const Eigen::Index r = from[t];
      const double wanted = floors[static_cast<size_t>(ja)] + heights(r, ja) * band;
      s.lift[t] = weight[t] * (wanted - world(r, 3 * ca + 1));
    }
    raise_leg(world, leg, rig.legs, rig.leg_length, s.lift);
    largest = std::max(largest, s.lift.cwiseAbs().maxCoeff());
    if (ct < 0 || ct != leg.toe) continue;
    // ...then the toe to its height about the ankle, the foot keeping its length and its way
    // across the floor.
    nearest_held(held, s.planted, jt, ramp, weight, from);
    for (Eigen::Index t = 0; t < frames; ++t) {
      if (from[t] < 0) continue;
      const Eigen::Index r = from[t];
      const double wanted = floors[static_cast<size_t>(jt)] + heights(r, jt) * band;
      const double change = weight[t] * (wanted - world(r, 3 * ct + 1));
      if (change == 0.0) continue;
      const Eigen::Vector3d ankle = joint_at(world, t, ca);
      const Eigen::Vector3d foot = joint_at(world, t, ct) - ankle;
      const double length = foot.norm(), across = std::hypot(foot.x(), foot.z());
      if (!(length > 0.0) || !(across > 0.0)) continue;
      // The foot turns about the ankle in its own vertical plane, the toe along an arc at most
      // kToeArcOverChange times the change long: a foot pointing nearly straight down (a kick's
      // swing eased into a plant) is not tipped on end, its toe swept under the ankle, for a
      // small change of height.
      const double pitch = std::atan2(foot.y(), across);
      const double wanted_pitch = std::asin(std::clamp((foot.y() + change) / length, -1.0, 1.0));
      const double turn = kToeArcOverChange * std::abs(change) / length;
      const double turned = std::clamp(wanted_pitch, pitch - turn, pitch + turn);
      const double up = length * std::sin(turned);
      const double scale = length * std::cos(turned) / across;
      set_joint(world, t, ct, ankle + Eigen::Vector3d(foot.x() * scale, up, foot.z() * scale));
      largest = std::max(largest, std::abs(up - foot.y()));
    }
  }
  return largest;
}

}  // namespace mostyle
