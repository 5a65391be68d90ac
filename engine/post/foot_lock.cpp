#include "engine/post/foot_lock.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/base/error.h"
#include "engine/kinematics/ease.h"
#include "engine/kinematics/joint_rows.h"
#include "engine/kinematics/two_bone_ik.h"
#include "engine/measure/planted_feet.h"
#include "engine/post/leg_move.h"

namespace mostyle {
namespace {

// A bend (knee off the hip-target line) shorter than this fraction of the leg has no usable
// direction: the previous frame's is used instead.
constexpr double kStraightLeg = kStraightChain;
// Bisection steps for a stance's fitting shift (fitting_shift): 2^-30 of the balanced shift.
constexpr int kFitShiftSteps = 30;
// How far (leg lengths) the knee's pole leans towards where the foot points (apply_foot_lock).
constexpr double kKneeForwardBias = 0.02;
// The toe bias is whole once the lock moves the ankle this many leg lengths, less below.
constexpr double kKneeBiasMove = 0.05;
// The lock keeps the ankle within this fraction of the leg's full length from the hip.
constexpr double kReachMargin = 0.995;
constexpr double kPi = 3.14159265358979323846;
// A knee bent less than this many leg lengths off its hip-ankle line keeps the bend direction
// it had on the frame before, in part (all of it when straight), where the lock moves the ankle.
constexpr double kKneeHold = 0.1;
// Where the leg's reach held the lock's offset back, it catches up at most this many leg lengths
// a second faster than its target moves.
constexpr double kOffsetCatchUp = 0.5;
// Where the lock allows part of the takes' planted moves, it tries this many shares beyond all
// and none, and stops once the planted feet move this close to (under) their limit.
constexpr int kShareRounds = 5;
constexpr double kShareClose = 0.97;
// A planted joint at the top of the planted band still has this weight in the foot's step.
constexpr double kMinAnchorWeight = 0.1;
// The body comes down at most this many leg lengths for the pinned feet to be within reach: a
// knee bent further would read as a crouch the takes do not make.
constexpr double kMaxBodyDrop = 0.05;

// One leg as the lock's steps see it: its columns, and its ankle's and toe's foot joints
// (planted_feet.h order; a toe column of -1 where the rig has none).
struct LockedLeg {
  LegColumns columns;
  int joints[2];
};

// The stances of frames the leg's foot is pinned over (scratch.pinned, scratch.stances): every frame one
// of its joints is planted (planted_feet.h, the measure the output is judged by), breaks of up to
// max_gap filled. Short stances are kept: a planted step left out would slide. O(F).
void find_stances(const LockedLeg& leg, int max_gap, FootLockScratch& s) {
  const Eigen::Index frames = s.planted.rows();
  s.pinned.resize(frames);
  // A joint the rig lacks (a toeless leg's toe) has no height, which reads as held: not counted.
  const bool toe = leg.columns.toe >= 0;
  auto held = [&](Eigen::Index t) {
    return s.held != nullptr && ((*s.held)(t, leg.joints[0]) > 0.5 || (toe && (*s.held)(t, leg.joints[1]) > 0.5));
  };
  for (Eigen::Index t = 0; t < frames; ++t)
    s.pinned[t] = s.planted(t, leg.joints[0]) > 0.5 || s.planted(t, leg.joints[1]) > 0.5 || held(t);
  for (Eigen::Index t = 0; t < frames;) {
    if (s.pinned[t]) {
      ++t;
      continue;
    }
    Eigen::Index e = t;
    while (e < frames && !s.pinned[e]) ++e;
    if (t > 0 && e < frames && e - t <= max_gap) s.pinned.segment(t, e - t).setOnes();
    t = e;
  }
  s.stances.clear();
  for (Eigen::Index t = 0; t < frames;) {
    if (!s.pinned[t]) {
      ++t;
      continue;
    }
    Eigen::Index end = t;
    while (end + 1 < frames && s.pinned[end + 1]) ++end;
    s.stances.emplace_back(t, end);
    t = end + 1;
  }
}

// The heading (radians about the vertical) from a foot's ankle to its toe at frame t, each
// moved by (its x, z) first.
double foot_heading(const Eigen::MatrixXd& world, Eigen::Index t, int ankle, int toe, const Eigen::Vector2d& ankle_by,
                    const Eigen::Vector2d& toe_by) {
  return std::atan2(world(t, 3 * toe + 2) + toe_by.y() - world(t, 3 * ankle + 2) - ankle_by.y(),
                    world(t, 3 * toe) + toe_by.x() - world(t, 3 * ankle) - ankle_by.x());
}

double wrapped(double angle) { return std::remainder(angle, 2.0 * kPi); }

// Within each stance, the turn about the vertical (s.yaw) that holds the foot's heading where both
// its joints are planted, as stance_offsets holds its place: each step's turn beyond what the drift
// allows (share of it; never more than the step turned) taken out, centred on the stance, and faded
// out over `ramp` frames either side of it; the toe is turned about the ankle by it (its height
// and its distance from the ankle kept). The offset, which moves the foot by its joints' averaged
// step, then holds both: a foot the mix turns from frame to frame (the style's legs turning it,
// on a content that stands still) would otherwise keep half of each joint's move, the ankle
// and the toe going opposite ways. O(F).
void hold_foot_heading(Eigen::MatrixXd& world, const LockedLeg& leg, const Eigen::MatrixXd* drift, double share,
                       int ramp, FootLockScratch& s) {
  const int ankle = leg.columns.ankle, toe = leg.columns.toe;
  const Eigen::Index frames = world.rows();
  s.yaw.setZero(frames);
  if (toe < 0 || ankle < 0) return;
  const int ja = leg.joints[0], jt = leg.joints[1];
  auto planted = [&](Eigen::Index t) { return s.planted(t, ja) > 0.5 && s.planted(t, jt) > 0.5; };
  const Eigen::Vector2d none = Eigen::Vector2d::Zero();
  for (const auto& [start, end] : s.stances) {
    for (Eigen::Index u = start; u < end; ++u) {
      s.yaw[u + 1] = s.yaw[u];
      if (!planted(u) || !planted(u + 1)) continue;
      const double from = foot_heading(world, u, ankle, toe, none, none);
      const double turned = wrapped(foot_heading(world, u + 1, ankle, toe, none, none) - from);
      double allowed = 0.0;
      if (drift != nullptr) {
        const Eigen::Vector2d ankle_by = share * Eigen::Vector2d((*drift)(u, 2 * ja), (*drift)(u, 2 * ja + 1));
        const Eigen::Vector2d toe_by = share * Eigen::Vector2d((*drift)(u, 2 * jt), (*drift)(u, 2 * jt + 1));
        allowed = std::clamp(wrapped(foot_heading(world, u, ankle, toe, ankle_by, toe_by) - from), -std::abs(turned),
                             std::abs(turned));
      }
      s.yaw[u + 1] += allowed - turned;
    }
    auto stance = s.yaw.segment(start, end - start + 1);
    stance.array() -= stance.mean();
  }
  for (size_t r = 0; r < s.stances.size(); ++r) {
    const auto [start, end] = s.stances[r];
    const Eigen::Index before = r > 0 ? s.stances[r - 1].second + 1 : 0;
    const Eigen::Index after = r + 1 < s.stances.size() ? s.stances[r + 1].first - 1 : frames - 1;
    for (Eigen::Index u = std::max(before, start - ramp); u < start; ++u)
      s.yaw[u] += smoothstep(1.0 - static_cast<double>(start - u) / (ramp + 1)) * s.yaw[start];
    for (Eigen::Index u = end + 1; u <= std::min(after, end + ramp); ++u)
      s.yaw[u] += smoothstep(1.0 - static_cast<double>(u - end) / (ramp + 1)) * s.yaw[end];
  }
  for (Eigen::Index t = 0; t < frames; ++t) {
    if (s.yaw[t] == 0.0) continue;
    const double c = std::cos(s.yaw[t]), n = std::sin(s.yaw[t]);
    const double dx = world(t, 3 * toe) - world(t, 3 * ankle), dz = world(t, 3 * toe + 2) - world(t, 3 * ankle + 2);
    world(t, 3 * toe) = world(t, 3 * ankle) + c * dx - n * dz;
    world(t, 3 * toe + 2) = world(t, 3 * ankle + 2) + n * dx + c * dz;
  }
}

// Where a foot joint counts as planted (planted_feet.h): within `height` of its floor.
struct PlantedBand {
  std::array<int, kFootJoints> columns;    // each foot joint's column in world, -1 where the rig has none
  std::array<double, kFootJoints> floors;  // each one's floor height
  double height = 0.0;
};

// Within each stance, the offset (s.target) that takes out, step by step, what the foot's planted
// joints move beyond what they may (share of drift; none: nothing), so they move by that much and never
// faster than they did; centred on the stance (the least total correction). A step's move is its
// planted joints' averaged, each weighted by how near it is to its floor (a heel lifting off
// leaves the toe to hold the foot; a toe coming down, the heel); a step with neither joint
// planted at both ends (a filled break) keeps the offset. O(F).
void stance_offsets(const Eigen::MatrixXd& world, const LockedLeg& leg, const PlantedBand& within,
                 const Eigen::MatrixXd* drift, double share, FootLockScratch& s) {
  const std::array<int, kFootJoints>& columns = within.columns;
  const std::array<double, kFootJoints>& floors = within.floors;
  const double band = within.height;
  for (const auto& [start, end] : s.stances) {
    s.target.row(start).setZero();
    for (Eigen::Index u = start; u < end; ++u) {
      double weights = 0.0;
      Eigen::Vector2d moved = Eigen::Vector2d::Zero(), allowed = Eigen::Vector2d::Zero();
      for (int j : leg.joints) {
        const int c = columns[static_cast<size_t>(j)];
        if (c < 0 || s.planted(u, j) <= 0.5 || s.planted(u + 1, j) <= 0.5) continue;
        const double height = std::max(world(u, 3 * c + 1), world(u + 1, 3 * c + 1)) - floors[static_cast<size_t>(j)];
        const double w = std::clamp(1.0 - height / band, kMinAnchorWeight, 1.0);
        moved += w * Eigen::Vector2d(world(u + 1, 3 * c) - world(u, 3 * c), world(u + 1, 3 * c + 2) - world(u, 3 * c + 2));
        if (drift != nullptr) allowed += share * w * Eigen::Vector2d((*drift)(u, 2 * j), (*drift)(u, 2 * j + 1));
        weights += w;
      }
      if (weights > 0.0) {
        moved /= weights;
        allowed /= weights;
        if (allowed.norm() > moved.norm()) allowed *= moved.norm() / allowed.norm();  // never faster
      } else {
        allowed = moved;
      }
      s.target.row(u + 1) = s.target.row(u) + (allowed - moved).transpose();
    }
    auto rows = s.target.middleRows(start, end - start + 1);
    rows.rowwise() -= rows.colwise().mean().eval();
  }
}

// How far the offset has gone from one stance's to the next's at each frame of the swings between
// stances (s.swing: 0 at a stance's last frame, 1 at the next's first). Each step takes a share of the
// change that grows with the room the foot has under `fastest` (units a frame) on that step, its
// ankle's or toe's own speed taken off, times a bump that starts and ends at zero (no jump in
// speed at lift-off or landing): the change goes where the swinging foot is slow, not where it is
// fastest. A plain smoothstep put most of it mid-swing, where a foot is at its fastest, and left
// the lock no room to pin a stride the takes' feet do not take (a style's shorter steps under the
// content's pace). Without a limit (fastest 0), the bump alone. O(F).
void swing_profile(const Eigen::MatrixXd& world, const LockedLeg& leg, double fastest, FootLockScratch& s) {
  const Eigen::Index frames = world.rows();
  s.swing.setZero(frames);
  for (size_t r = 1; r < s.stances.size(); ++r) {
    const Eigen::Index from = s.stances[r - 1].second, to = s.stances[r].first, span = to - from;
    auto bump = [&](Eigen::Index u) { return std::pow(std::sin(kPi * (double(u - from) + 0.5) / double(span)), 2); };
    double total = 0.0;
    for (Eigen::Index u = from; u < to; ++u) {  // the step u -> u + 1
      double room = 1.0;
      if (fastest > 0.0) {
        double own = 0.0;
        for (int c : {leg.columns.ankle, leg.columns.toe})
          if (c >= 0) own = std::max(own, (joint_at(world, u + 1, c) - joint_at(world, u, c)).norm());
        room = std::max(0.0, fastest - own);
      }
      total += bump(u) * room;
      s.swing[u + 1] = total;
    }
    if (!(total > 0.0)) {  // no step with room: the bump alone (the stance is then not pinned)
      total = 0.0;
      for (Eigen::Index u = from; u < to; ++u) s.swing[u + 1] = total += bump(u);
    }
    for (Eigen::Index u = from + 1; u <= to; ++u) s.swing[u] /= total;
  }
}

// The shift (taken off every offset of a stance) that lets a stance's offsets at its ends (first,
// last) fit the rooms before and after it, or come as near as they can: the offsets are centred
// on the stance (the least total correction), so where one side's swing has little room and the
// other's much, the whole pin would be scaled down to the smaller room although moving the pinned
// spot towards the roomier side fits it. The shift goes from none towards the balanced one (the
// two ends' offsets in proportion to their rooms, the largest fit), only as far as the fit needs
// (bisection on that way; each end's distance is convex along it, so where the balanced shift
// fits, the shifts that fit from there back towards none are one stretch). A stance that fits as it
// is gets none. O(1).
Eigen::RowVector2d fitting_shift(const Eigen::RowVector2d& first, const Eigen::RowVector2d& last, double before,
                                 double after) {
  auto fits = [&](const Eigen::RowVector2d& shift) {
    return (first - shift).norm() <= before && (last - shift).norm() <= after;
  };
  if (fits(Eigen::RowVector2d::Zero())) return Eigen::RowVector2d::Zero();
  double towards_last;  // the balanced shift: first + towards_last (last - first)
  if (std::isinf(before) && std::isinf(after)) return Eigen::RowVector2d::Zero();
  if (std::isinf(before)) towards_last = 1.0;
  else if (std::isinf(after)) towards_last = 0.0;
  else if (before + after > 0.0) towards_last = before / (before + after);
  else return Eigen::RowVector2d::Zero();
  const Eigen::RowVector2d balanced = first + towards_last * (last - first);
  if (!fits(balanced)) return balanced;
  double lo = 0.0, hi = 1.0;  // lo does not fit, hi does
  for (int i = 0; i < kFitShiftSteps; ++i) {
    const double mid = 0.5 * (lo + hi);
    (fits(mid * balanced) ? hi : lo) = mid;
  }
  return hi * balanced;
}

// Each stance's offsets, shifted as fitting_shift finds, then scaled down where the change of offset before or after it (spread over a
// swing as s.swing shares it, or a fade) would move the foot faster than `fastest` units a frame: on every step of the
// swing the foot's own speed plus the offset's change at most that (each stance may take half of a
// swing's room, a fade's whole). A stance next to a swing of a few frames (a foot that barely leaves
// the band) or a swing already near the takes' fastest is pinned in part rather than make the
// swinging foot pop. O(F).
void fit_to_swings(const Eigen::MatrixXd& world, const LockedLeg& leg, int ramp, double fastest, FootLockScratch& s) {
  const Eigen::Index frames = world.rows();
  auto room = [&](Eigen::Index first, Eigen::Index last, auto ease) {  // steps first -> last
    double out = std::numeric_limits<double>::infinity();
    for (Eigen::Index u = std::max<Eigen::Index>(first, 0); u < std::min(last, frames - 1); ++u) {
      const double change = std::abs(ease(u + 1) - ease(u));
      if (!(change > 0.0)) continue;
      double own = 0.0;
      for (int c : {leg.columns.ankle, leg.columns.toe})
        if (c >= 0) own = std::max(own, (joint_at(world, u + 1, c) - joint_at(world, u, c)).norm());
      out = std::min(out, std::max(0.0, fastest - own) / change);
    }
    return out;
  };
  for (size_t r = 0; r < s.stances.size(); ++r) {
    // Plain variables, not a structured binding: C++17 lambdas cannot capture those.
    const Eigen::Index start = s.stances[r].first, end = s.stances[r].second;
    double before, after;
    if (r == 0) {
      before = room(start - ramp - 1, start, [&](Eigen::Index u) {
        return u >= start ? 1.0 : u < start - ramp ? 0.0 : smoothstep(1.0 - double(start - u) / (ramp + 1));
      });
    } else {
      const Eigen::Index from = s.stances[r - 1].second;
      before = 0.5 * room(from, start, [&](Eigen::Index u) { return u <= from ? 0.0 : s.swing[u]; });
    }
    if (r + 1 == s.stances.size()) {
      after = room(end, end + ramp + 1, [&](Eigen::Index u) {
        return u <= end ? 1.0 : u > end + ramp ? 0.0 : smoothstep(1.0 - double(u - end) / (ramp + 1));
      });
    } else {
      const Eigen::Index to = s.stances[r + 1].first;
      after = 0.5 * room(end, to, [&](Eigen::Index u) { return u <= end ? 0.0 : s.swing[u]; });
    }
    auto rows = s.target.middleRows(start, end - start + 1);
    rows.rowwise() -= fitting_shift(rows.row(0), rows.row(end - start), before, after);
    const double at_start = rows.row(0).norm(), at_end = rows.row(end - start).norm();
    double scale = 1.0;
    if (at_start > before) scale = std::min(scale, before / at_start);
    if (at_end > after) scale = std::min(scale, after / at_end);
    rows *= scale;
  }
}

// The offsets between stances (s.target, s.weight 1 wherever the ankle moves, s.ease): the change
// from one stance to the next spread over the whole swing as swing_profile shares it (s.swing: no
// jump in speed at landing or lift-off, most of it on the swing's slow steps); before the first
// stance and after the last a fade over ramp frames. O(F).
void ease_between_stances(Eigen::Index frames, int ramp, FootLockScratch& s) {
  s.weight.setZero(frames);
  s.ease.setConstant(frames, -1.0);
  for (size_t r = 0; r < s.stances.size(); ++r) {
    const auto [start, end] = s.stances[r];
    s.weight.segment(start, end - start + 1).setOnes();
    if (r > 0) {  // the swing from the previous stance
      const Eigen::Index previous_end = s.stances[r - 1].second;
      for (Eigen::Index u = previous_end + 1; u < start; ++u) {
        const double f = s.swing[u];
        s.weight[u] = 1.0;
        s.ease[u] = f;
        s.target.row(u) = (1.0 - f) * s.target.row(previous_end) + f * s.target.row(start);
      }
    } else {  // fade in before the first stance
      for (Eigen::Index u = std::max<Eigen::Index>(0, start - ramp); u < start; ++u) {
        const double f = smoothstep(1.0 - static_cast<double>(start - u) / (ramp + 1));
        s.weight[u] = 1.0;
        s.target.row(u) = f * s.target.row(start);
      }
    }
    if (r + 1 == s.stances.size())  // fade out after the last stance
      for (Eigen::Index u = end + 1; u <= std::min(frames - 1, end + ramp); ++u) {
        const double f = smoothstep(1.0 - static_cast<double>(u - end) / (ramp + 1));
        s.weight[u] = 1.0;
        s.ease[u] = 1.0 - f;
        s.target.row(u) = f * s.target.row(end);
      }
  }
}

// The knee's bend direction for the IK (its pole) at frame t: taken from the leg's own pose, the
// knee's offset from its hip-ankle line. Taken from the hip-target line instead, it would swing
// round whenever the lock pulls the ankle across the knee's plane, and a knee the motion leaves
// nearly straight would fold backwards. A slight bias towards where the foot points keeps the pole
// from passing through zero as the leg straightens; where the knee is nearly straight its bend
// can still turn round from one frame to the next (the knee crossing its hip-ankle line), so the
// bend it had on the frame before (as locked) holds it, the more the straighter the knee. Both
// fade as the ankle moves less (`moved`): a lock that does not move the ankle leaves the leg as
// it was. O(1).
// The way the body faces at frame t, horizontal, not normalized: its hips' left-right line
// turned a quarter about the vertical; zero where the rig lacks a hip.
template <typename Matrix>
Eigen::Vector3d body_facing(const Matrix& world, const std::array<LegColumns, 2>& rig_legs, Eigen::Index t) {
  if (rig_legs[0].hip < 0 || rig_legs[1].hip < 0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d across = joint_at(world, t, rig_legs[0].hip) - joint_at(world, t, rig_legs[1].hip);
  return Eigen::Vector3d(-across.z(), 0.0, across.x());  // across x up
}

template <typename Matrix>
Eigen::Vector3d knee_pole(const Matrix& world, const LegColumns& leg,
                          const std::array<LegColumns, 2>& rig_legs, Eigen::Index t, double moved, double leg_length) {
  const Eigen::Vector3d hip = joint_at(world, t, leg.hip), ankle = joint_at(world, t, leg.ankle);
  const Eigen::Vector3d leg_line = ankle - hip;
  Eigen::Vector3d pole = joint_at(world, t, leg.knee) - hip;
  if (leg_line.squaredNorm() > 0) pole -= leg_line * (leg_line.dot(pole) / leg_line.squaredNorm());
  const double moving = std::clamp(moved / (kKneeBiasMove * leg_length), 0.0, 1.0);
  // A knee bends forwards, the way the body faces (its hips' left-right line turned a quarter
  // about the vertical): a mix of poses can bend it a little backwards (a hyperextended knee), and
  // the IK would fold the leg backwards along that as it moves the ankle. Its backward part is
  // dropped as the ankle is moved (a lock that does not move the ankle leaves the leg as it
  // was): such a knee is straight, and the bias below bends it forwards.
  const Eigen::Vector3d facing = body_facing(world, rig_legs, t);
  if (facing.norm() > 0) {
    const double back = pole.dot(facing.normalized());
    if (back < 0.0) pole -= moving * back * facing.normalized();
  }
  const double bend = pole.norm();
  // The toe bias fades out as the knee bends more (gone at three times its size).
  const double bias = std::clamp(1.0 - bend / (3.0 * kKneeForwardBias * leg_length), 0.0, 1.0) * moving;
  if (leg.toe >= 0 && bias > 0.0) {
    Eigen::Vector3d forward = joint_at(world, t, leg.toe) - ankle;
    forward.y() = 0.0;
    if (forward.norm() > 0) pole += bias * kKneeForwardBias * leg_length * forward.normalized();
  }
  const double hold = (1.0 - std::clamp(bend / (kKneeHold * leg_length), 0.0, 1.0)) * moving;
  if (t > 0 && hold > 0.0) {
    const Eigen::Vector3d h0 = joint_at(world, t - 1, leg.hip);
    const Eigen::Vector3d line0 = joint_at(world, t - 1, leg.ankle) - h0;
    Eigen::Vector3d before = joint_at(world, t - 1, leg.knee) - h0;
    if (line0.squaredNorm() > 0) before -= line0 * (line0.dot(before) / line0.squaredNorm());
    if (before.norm() > kStraightLeg * leg_length) pole += hold * kKneeHold * leg_length * before.normalized();
  }
  return pole;
}

// Moves the leg's ankle by its offset on every frame with weight (two-bone IK, the toe translated
// with it). An offset that would take the ankle out of the leg's reach is shortened to it: the IK
// would lift the ankle along the straightened leg and let the knee snap back when the lock lets
// go. What the reach held back is caught up no faster than the target moves plus kOffsetCatchUp
// (all at once, a leg bending from straight in a few frames would free a whole stance's pinning
// in a jump), and what follows a stance eases from where the foot was, not from where the leg could
// not reach. O(F).
// rig_legs: the legs' columns in world (their hips read for the way the body faces).
template <typename Matrix>
void move_leg(Matrix& world, const LegColumns& leg, const std::array<LegColumns, 2>& rig_legs, const FootRig& rig,
              FootLockScratch& s) {
  const Eigen::Index frames = world.rows();
  // The knee's bend direction where the leg is straight: the last frame's, within a second,
  // where it was not (none: the IK picks one).
  const Eigen::Index search = static_cast<Eigen::Index>(std::ceil(rig.fps));
  auto last_bend = [&](Eigen::Index t) -> Eigen::Vector3d {
    for (Eigen::Index u = t; u >= std::max<Eigen::Index>(0, t - search); --u) {
      const Eigen::Vector3d hip = joint_at(world, u, leg.hip);
      const Eigen::Vector3d along = joint_at(world, u, leg.ankle) - hip;
      const Eigen::Vector3d knee = joint_at(world, u, leg.knee) - hip;
      if (!(along.norm() > 0)) continue;
      const Eigen::Vector3d b = knee - along * along.dot(knee) / along.squaredNorm();
      if (b.norm() > kStraightLeg * along.norm()) return b;
    }
    return Eigen::Vector3d::Zero();
  };
  // The offset applied on the frame before (0 where the lock left the leg alone), the target
  // then, and how much the offset fell short of the target on the last frame of the last stance.
  Eigen::Vector2d applied = Eigen::Vector2d::Zero(), wanted_before = Eigen::Vector2d::Zero();
  Eigen::Vector2d short_of = Eigen::Vector2d::Zero();
  const double catch_up = kOffsetCatchUp * rig.leg_length / rig.fps;
  for (Eigen::Index t = 0; t < frames; ++t) {
    if (s.weight[t] <= 0.0) {
      applied.setZero();
      continue;
    }
    const Eigen::Vector3d hip = joint_at(world, t, leg.hip);
    const Eigen::Vector3d knee = joint_at(world, t, leg.knee);
    const Eigen::Vector3d ankle = joint_at(world, t, leg.ankle);
    // (A leg already straighter than the margin may stay as straight.)
    const double reach = std::max(kReachMargin * ((knee - hip).norm() + (ankle - knee).norm()), (ankle - hip).norm());
    auto within_reach = [&](const Eigen::Vector2d& offset) -> Eigen::Vector2d {
      const Eigen::Vector3d d = ankle - hip, o(offset.x(), 0.0, offset.y());
      if ((d + o).norm() <= reach) return offset;
      // |ankle - hip + f (ox, 0, oz)| = reach: the positive root f, within [0, 1].
      const double a = o.squaredNorm(), b = 2.0 * d.dot(o), c = d.squaredNorm() - reach * reach;
      const double disc = b * b - 4.0 * a * c;
      const double f = a > 0 && disc >= 0 ? std::clamp((-b + std::sqrt(disc)) / (2.0 * a), 0.0, 1.0) : 0.0;
      return f * offset;
    };
    if (t > 0 && s.pinned[t - 1] && !s.pinned[t]) short_of = applied - s.target.row(t - 1).transpose();
    Eigen::Vector2d wanted = s.target.row(t).transpose();
    if (s.ease[t] >= 0.0) wanted += (1.0 - s.ease[t]) * short_of;
    if (s.record_drop) {
      // How far the hip must come down for the ankle to reach the wanted target with the knee
      // bent to the margin (a straighter leg's reach is its own length, which the drop shortens):
      // the hip's height above it less what that reach leaves once the horizontal distance is taken.
      const Eigen::Vector3d d = ankle - hip;
      const double bent = kReachMargin * ((knee - hip).norm() + (ankle - knee).norm());
      const double across = Eigen::Vector2d(d.x() + wanted.x(), d.z() + wanted.y()).squaredNorm();
      const double down = across < bent * bent ? -d.y() - std::sqrt(bent * bent - across) : -d.y();
      s.drop[t] = std::max(s.drop[t], down);
    }
    Eigen::Vector2d offset = within_reach(wanted);
    if (t > 0 && s.weight[t - 1] > 0.0) {
      const double limit = (wanted - wanted_before).norm() + catch_up;
      const Eigen::Vector2d change = offset - applied;
      if (change.norm() > limit) offset = within_reach(applied + change * (limit / change.norm()));
    }
    applied = offset;
    wanted_before = wanted;
    const Eigen::Vector3d target = ankle + Eigen::Vector3d(offset.x(), 0.0, offset.y());
    // The knee's bend turned with the leg (the least turn taking the hip-ankle line onto the
    // hip-target line): a bend measured across the old line, taken across the new one, can
    // point backwards when the leg is nearly straight and the target moves along it.
    const Eigen::Quaterniond turn = (ankle - hip).norm() > 0 && (target - hip).norm() > 0
                                        ? Eigen::Quaterniond::FromTwoVectors(ankle - hip, target - hip)
                                        : Eigen::Quaterniond::Identity();
    const Eigen::Vector3d pole = turn * knee_pole(world, leg, rig_legs, t, offset.norm(), rig.leg_length);
    const bool straight = !(pole.norm() > kStraightLeg * rig.leg_length);
    const Eigen::Vector3d before = straight ? Eigen::Vector3d(turn * last_bend(t)) : Eigen::Vector3d::Zero();
    TwoBoneIkJob ik;
    ik.start = hip;
    ik.mid = knee;
    ik.end = ankle;
    ik.target = target;
    ik.pole = straight ? before : pole;
    ik.bend_fallback = before;
    place_leg(world, t, leg, ik.Run());
  }
}

// move_leg on a copy of the joints it reads, one frame's values side by side (both hips, the
// knee, ankle and toe: in world they lie a column apart, a dozen memory streams at once), the
// knee, ankle and toe written back after: the same arithmetic on the same values. O(F).
void move_leg_rows(Eigen::MatrixXd& world, const LegColumns& leg, const FootRig& rig, FootLockScratch& s) {
  const int from[5] = {rig.legs[0].hip, rig.legs[1].hip, leg.knee, leg.ankle, leg.toe};
  s.leg_rows.resize(world.rows(), 15);
  for (int k = 0; k < 5; ++k)
    if (from[k] >= 0) s.leg_rows.middleCols(3 * k, 3) = world.middleCols(3 * from[k], 3);
  LegColumns rows_leg;
  rows_leg.hip = leg.hip == rig.legs[0].hip ? 0 : 1;
  rows_leg.knee = 2;
  rows_leg.ankle = 3;
  rows_leg.toe = leg.toe >= 0 ? 4 : -1;
  std::array<LegColumns, 2> rows_legs;
  rows_legs[0].hip = rig.legs[0].hip >= 0 ? 0 : -1;
  rows_legs[1].hip = rig.legs[1].hip >= 0 ? 1 : -1;
  move_leg(s.leg_rows, rows_leg, rows_legs, rig, s);
  for (int k = 2; k < 5; ++k)
    if (from[k] >= 0) world.middleCols(3 * from[k], 3) = s.leg_rows.middleCols(3 * k, 3);
}

// The lock keeps heights, so the same steps stay planted; it must not move the leg's planted
// joints more in all than they moved (where the leg could not reach its targets, say): then the
// leg is put back as it was (s.before: its knee, ankle and toe). O(F).
// before_moves: what the planted joints moved before the lock, as this sums it; NaN: not known
// yet (set here: every try of one apply_foot_lock starts from the same motion).
void keep_if_slower(Eigen::MatrixXd& world, const LockedLeg& leg, const std::array<int, kFootJoints>& columns,
                    FootLockScratch& s, double& before_moves) {
  const bool known = !std::isnan(before_moves);
  double before = 0.0, after = 0.0;
  for (int k = 0; k < 2; ++k) {
    const int j = leg.joints[k], c = columns[static_cast<size_t>(j)], b = 1 + k;  // b: its columns in s.before
    if (c < 0) continue;
    for (Eigen::Index t = 0; t + 1 < world.rows(); ++t) {
      if (s.planted(t, j) <= 0.5 || s.planted(t + 1, j) <= 0.5) continue;
      if (!known)
        before += horizontal_step(s.before(t + 1, 3 * b) - s.before(t, 3 * b), s.before(t + 1, 3 * b + 2) - s.before(t, 3 * b + 2));
      after += horizontal_step(world(t + 1, 3 * c) - world(t, 3 * c), world(t + 1, 3 * c + 2) - world(t, 3 * c + 2));
    }
  }
  if (known) before = before_moves;
  else before_moves = before;
  if (after > before)
    for (int b = 0; b < 3; ++b) {
      const int c = b == 0 ? leg.columns.knee : b == 1 ? leg.columns.ankle : leg.columns.toe;
      if (c >= 0) world.middleCols(3 * c, 3) = s.before.middleCols(3 * b, 3);
    }
}

// Both legs locked once, allowing `share` of the drift (apply_foot_lock); s.planted and floors
// are the motion's planted frames (planted_frames). O(F).
void lock_legs(Eigen::MatrixXd& world, const FootRig& rig, const std::array<double, kFootJoints>& floors,
               const Eigen::MatrixXd* drift, double share, double max_speed, FootLockScratch& scratch) {
  const Eigen::Index frames = world.rows();
  const int ramp = rig.blend_frames();
  const std::array<int, kFootJoints> columns = foot_joint_columns(rig);
  const PlantedBand within{columns, floors, kPlantedHeightFraction * rig.body_height};
  for (int side = 0; side < 2; ++side) {
    const LockedLeg leg{rig.legs[static_cast<size_t>(side)], {2 * side, 2 * side + 1}};
    if (!leg.columns.usable()) continue;
    for (int b = 0; b < 3; ++b) {
      const int c = b == 0 ? leg.columns.knee : b == 1 ? leg.columns.ankle : leg.columns.toe;
      if (c >= 0) scratch.before.middleCols(3 * b, 3) = world.middleCols(3 * c, 3);
    }
    find_stances(leg, rig.max_gap_frames(), scratch);
    scratch.target.setZero();
    hold_foot_heading(world, leg, drift, share, ramp, scratch);
    stance_offsets(world, leg, within, drift, share, scratch);
    swing_profile(world, leg, max_speed / rig.fps, scratch);
    if (max_speed > 0.0) fit_to_swings(world, leg, ramp, max_speed / rig.fps, scratch);
    ease_between_stances(frames, ramp, scratch);
    move_leg_rows(world, leg.columns, rig, scratch);
    keep_if_slower(world, leg, columns, scratch, scratch.before_moves[static_cast<size_t>(side)]);
  }
}

// The columns the lock moves (each usable leg's knee, ankle and toe: lock_legs changes no other)
// copied from world into `kept` (F x 18, three per joint), or back when `restore`: the lock's
// tries start from the motion as it was and keep the best, copying these alone.
void copy_leg_columns(Eigen::MatrixXd& world, const FootRig& rig, Eigen::MatrixXd& kept, bool restore) {
  if (!restore) kept.resize(world.rows(), 18);
  for (int side = 0; side < 2; ++side) {
    const LegColumns& leg = rig.legs[static_cast<size_t>(side)];
    if (!leg.usable()) continue;
    for (int b = 0; b < 3; ++b) {
      const int c = b == 0 ? leg.knee : b == 1 ? leg.ankle : leg.toe;
      if (c < 0) continue;
      if (restore) world.middleCols(3 * c, 3) = kept.middleCols(9 * side + 3 * b, 3);
      else kept.middleCols(9 * side + 3 * b, 3) = world.middleCols(3 * c, 3);
    }
  }
}

// The body brought down by s.drop (every joint but the legs' knees, ankles and toes), each leg's
// knee bent so that its ankle stays (two-bone IK from the lowered hip), on the frames it comes
// down. The knee bends the way it bends, leaning forwards (the way the hips face). O(F).
void lower_body(Eigen::MatrixXd& world, const FootRig& rig, const FootLockScratch& s) {
  const Eigen::Index joints = world.cols() / 3;
  std::vector<bool> below_hip(static_cast<size_t>(joints), false);
  for (const LegColumns& leg : rig.legs)
    for (int c : {leg.knee, leg.ankle, leg.toe})
      if (c >= 0) below_hip[static_cast<size_t>(c)] = true;
  for (Eigen::Index t = 0; t < world.rows(); ++t) {
    const double down = s.drop[t];
    if (!(down > 0.0)) continue;
    for (Eigen::Index j = 0; j < joints; ++j)
      if (!below_hip[static_cast<size_t>(j)]) world(t, 3 * j + 1) -= down;
    const Eigen::Vector3d facing = body_facing(world, rig.legs, t);
    for (const LegColumns& leg : rig.legs) {
      if (!leg.usable()) continue;
      const Eigen::Vector3d hip = joint_at(world, t, leg.hip), ankle = joint_at(world, t, leg.ankle);
      const Eigen::Vector3d lowered(0.0, down, 0.0);
      TwoBoneIkJob ik;
      ik.start = hip;
      ik.mid = joint_at(world, t, leg.knee) - lowered;
      ik.end = ankle - lowered;
      ik.target = ankle;
      // The knee's own bend, leaning forwards: a straight leg's bend is too small to say which way.
      ik.pole = ik.mid - ik.start;
      if (facing.norm() > 0) ik.pole += kKneeForwardBias * rig.leg_length * facing.normalized();
      ik.bend_fallback = facing;
      place_leg(world, t, leg, ik.Run());
    }
  }
}

// Where pinning the planted feet (allowing all of the drift: the takes' own planted moves need no
// room, so a take alone is left as it is) would take them beyond the legs' reach, the body
// brought down as far as that needs (a try of the lock records it), at most kMaxBodyDrop of the leg: the
// running maximum over twice blend_frames() either side, averaged over blend_frames() either
// side, so that every frame comes down at least as far as it needs and the change is gradual.
// The legs' columns are put back as they were before the try. False, the motion as it was, where
// no frame needs it. O(F x ramp).
bool drop_for_reach(Eigen::MatrixXd& world, const FootRig& rig, const std::array<double, kFootJoints>& floors,
                    const Eigen::MatrixXd* drift, const FootLockLimits& limits, FootLockScratch& s) {
  const Eigen::Index frames = world.rows();
  copy_leg_columns(world, rig, s.original, false);
  s.drop.setZero(frames);
  s.record_drop = true;
  lock_legs(world, rig, floors, drift, 1.0, limits.fastest_joint, s);
  s.record_drop = false;
  copy_leg_columns(world, rig, s.original, true);
  s.drop = s.drop.cwiseMax(0.0).cwiseMin(kMaxBodyDrop * rig.leg_length);
  if (!(s.drop.maxCoeff() > 0.0)) return false;
  const Eigen::Index ramp = rig.blend_frames();
  s.drop_max.resize(frames);
  for (Eigen::Index t = 0; t < frames; ++t) {
    const Eigen::Index a = std::max<Eigen::Index>(0, t - 2 * ramp), b = std::min(frames - 1, t + 2 * ramp);
    s.drop_max[t] = s.drop.segment(a, b - a + 1).maxCoeff();
  }
  for (Eigen::Index t = 0; t < frames; ++t) {
    const Eigen::Index a = std::max<Eigen::Index>(0, t - ramp), b = std::min(frames - 1, t + ramp);
    s.drop[t] = s.drop_max.segment(a, b - a + 1).mean();
  }
  lower_body(world, rig, s);
  return true;
}

// The lock, allowing as much of the drift as keeps the planted feet under limits.planted_speed
// (apply_foot_lock); the planted feet's measure it leaves. Needs a drift and a limit.
double lock_within_limit(Eigen::MatrixXd& world, const FootRig& rig, const std::array<double, kFootJoints>& floors,
                         const Eigen::MatrixXd* drift, const FootLockLimits& limits, FootLockScratch& scratch);

}  // namespace

void apply_foot_lock(Eigen::MatrixXd& world, const FootRig& rig, FootLockScratch& scratch, const Eigen::MatrixXd* drift,
                     const FootLockLimits& limits, const Eigen::MatrixXd* held) {
  if (held != nullptr && (held->rows() != world.rows() || held->cols() != kFootJoints))
    throw InputError("foot lock: expected the takes' planted feet as " + std::to_string(world.rows()) + " x " +
                     std::to_string(kFootJoints));
  scratch.held = held;
  if (drift != nullptr && (drift->rows() != world.rows() || drift->cols() != 2 * kFootJoints))
    throw InputError("foot lock: expected the planted feet's drift as " + std::to_string(world.rows()) + " x " +
                     std::to_string(2 * kFootJoints));
  rig.check_columns(world, "foot lock");
  const Eigen::Index frames = world.rows();
  scratch.target.resize(frames, 2);
  scratch.before.resize(frames, 9);
  std::array<double, kFootJoints> floors;
  planted_frames(world, rig, scratch.planted, scratch.heights, &floors);
  scratch.before_moves.fill(std::numeric_limits<double>::quiet_NaN());
  if (drift == nullptr || !(limits.planted_speed > 0.0)) {
    lock_legs(world, rig, floors, drift, 1.0, limits.fastest_joint, scratch);
    return;
  }
  // Locked as the legs stand; where that leaves the planted feet faster than the limit, and it
  // is the legs' reach that held the pin back (a content standing on straight legs under a style
  // that sways its hips), the body comes down and the legs are locked again from there. A take
  // alone, its planted feet its own, is never lowered.
  copy_leg_columns(world, rig, scratch.unlocked, false);
  if (lock_within_limit(world, rig, floors, drift, limits, scratch) <= limits.planted_speed) return;
  copy_leg_columns(world, rig, scratch.locked, false);
  copy_leg_columns(world, rig, scratch.unlocked, true);
  if (!drop_for_reach(world, rig, floors, drift, limits, scratch)) {
    copy_leg_columns(world, rig, scratch.locked, true);
    return;
  }
  scratch.before_moves.fill(std::numeric_limits<double>::quiet_NaN());
  lock_within_limit(world, rig, floors, drift, limits, scratch);
}

namespace {

double lock_within_limit(Eigen::MatrixXd& world, const FootRig& rig, const std::array<double, kFootJoints>& floors,
                         const Eigen::MatrixXd* drift, const FootLockLimits& limits, FootLockScratch& scratch) {
  // Allowing all the drift, the planted feet may still move faster than planted_speed (the
  // output's planted steps fall where the takes' move most); then less of it is allowed: none,
  // and if that is under the limit, the largest share found (regula falsi, Illinois' variant: the
  // measure need not be straight in the share, a few tries) that keeps the measure under it: the
  // least pinning that holds the limit. The heights stay, so one planted mask serves every try.
  const double limit = limits.planted_speed;
  copy_leg_columns(world, rig, scratch.original, false);
  lock_legs(world, rig, floors, drift, 1.0, limits.fastest_joint, scratch);
  double high = 1.0, at_high = planted_speed(world, scratch.planted, rig).speed;
  if (at_high <= limit) return at_high;
  copy_leg_columns(world, rig, scratch.original, true);
  lock_legs(world, rig, floors, drift, 0.0, limits.fastest_joint, scratch);
  double low = 0.0, at_low = planted_speed(world, scratch.planted, rig).speed;
  if (at_low >= limit) return at_low;
  copy_leg_columns(world, rig, scratch.best, false);  // the motion at `low`, under the limit
  // Distances from the limit, the one kept twice in a row halved (Illinois).
  double below = limit - at_low, above = at_high - limit;
  int kept = 0;  // > 0: low kept that many rounds in a row, < 0: high
  for (int round = 0; round < kShareRounds && at_low < kShareClose * limit; ++round) {
    const double share = low + below / (below + above) * (high - low);
    copy_leg_columns(world, rig, scratch.original, true);
    lock_legs(world, rig, floors, drift, share, limits.fastest_joint, scratch);
    const double at = planted_speed(world, scratch.planted, rig).speed;
    if (at <= limit) {
      low = share;
      at_low = at;
      below = limit - at;
      copy_leg_columns(world, rig, scratch.best, false);
      kept = kept < 0 ? kept - 1 : -1;
      if (kept <= -2) above *= 0.5;
    } else {
      high = share;
      above = at - limit;
      kept = kept > 0 ? kept + 1 : 1;
      if (kept >= 2) below *= 0.5;
    }
  }
  copy_leg_columns(world, rig, scratch.best, true);
  return at_low;
}

}  // namespace

}  // namespace mostyle
