#include "engine/post/foot_contact.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "engine/io/error.h"
#include "engine/kinematics/ease.h"
#include "engine/post/planted_feet.h"
#include "engine/prepare/major_skeleton.h"
#include "engine/prepare/major_take.h"

namespace mostyle {
namespace {

constexpr double kFloorPercentile = 0.05;  // of the ankle's heights: its height when planted
constexpr double kTimeEpsilon = 1e-9;
// A bend (knee off the hip-target line) shorter than this fraction of the leg has no usable
// direction: the previous frame's is used instead.
constexpr double kStraightLeg = 1e-4;
// Fraction of the leg's length the IK keeps away from full extension or folding.
constexpr double kExtensionMargin = 1e-9;
// How far (leg lengths) the knee's pole leans towards where the foot points (apply_foot_lock).
constexpr double kKneeForwardBias = 0.02;
// The toe bias is whole once the lock moves the ankle this many leg lengths, less below.
constexpr double kKneeBiasMove = 0.05;
// The lock keeps the ankle within this fraction of the leg's full length from the hip.
constexpr double kReachMargin = 0.995;

Eigen::Vector3d joint_at(const Eigen::MatrixXd& m, Eigen::Index row, int column) {
  return Eigen::Vector3d(m(row, 3 * column), m(row, 3 * column + 1), m(row, 3 * column + 2));
}

void set_joint(Eigen::MatrixXd& m, Eigen::Index row, int column, const Eigen::Vector3d& v) {
  m(row, 3 * column) = v.x();
  m(row, 3 * column + 1) = v.y();
  m(row, 3 * column + 2) = v.z();
}

int seconds_to_frames(double seconds, double fps) {
  return static_cast<int>(std::floor(seconds * fps + kTimeEpsilon));
}

void check_columns(const Eigen::MatrixXd& world, const FootRig& rig, const char* where) {
  for (const LegColumns& leg : rig.legs) {
    for (int c : {leg.hip, leg.knee, leg.ankle, leg.toe}) {
      if (c >= 0 && 3 * static_cast<Eigen::Index>(c) + 2 >= world.cols())
        throw InputError(std::string(where) + ": positions have " + std::to_string(world.cols()) +
                         " columns, too few for joint column " + std::to_string(c));
    }
  }
}

void check_contacts(const Eigen::MatrixXd& world, const Eigen::MatrixXd& contacts, const char* where) {
  if (contacts.rows() != world.rows() || contacts.cols() != 2)
    throw InputError(std::string(where) + ": expected " + std::to_string(world.rows()) +
                     " x 2 contacts, found " + std::to_string(contacts.rows()) + " x " +
                     std::to_string(contacts.cols()));
}


// Any unit vector perpendicular to n (unit).
Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d axis = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(axis).normalized();
}

}  // namespace

void FootContactOptions::Validate() const {
  const double values[] = {height_fraction, speed_fraction, min_contact_seconds, max_gap_seconds,
                           blend_seconds};
  const char* names[] = {"height fraction", "speed fraction", "minimum contact time", "maximum gap",
                         "lock blend time"};
  for (int i = 0; i < 5; ++i) {
    if (!(values[i] >= 0) || !std::isfinite(values[i]))
      throw InputError(std::string("foot contacts: expected a finite ") + names[i] + " of 0 or more, found " +
                       std::to_string(values[i]));
  }
}

int FootRig::blend_frames() const {
  return std::max(1, static_cast<int>(std::lround(options.blend_seconds * fps)));
}

FootRig make_foot_rig(const std::vector<int>& majors, const std::vector<double>& lengths, double fps,
                      const FootContactOptions& options) {
  options.Validate();
  if (!(fps > 0) || !std::isfinite(fps))
    throw InputError("foot contacts: expected a positive frame rate, found " + std::to_string(fps));
  if (lengths.size() != majors.size())
    throw InputError("foot contacts: " + std::to_string(lengths.size()) + " bone lengths for " +
                     std::to_string(majors.size()) + " joints");
  FootRig rig;
  rig.fps = fps;
  rig.options = options;
  auto column = [&](MajorJoint j) { return major_column(majors, static_cast<int>(j)); };
  rig.legs[0] = {column(MajorJoint::kLeftHip), column(MajorJoint::kLeftKnee), column(MajorJoint::kLeftAnkle),
                 column(MajorJoint::kLeftToe)};
  rig.legs[1] = {column(MajorJoint::kRightHip), column(MajorJoint::kRightKnee),
                 column(MajorJoint::kRightAnkle), column(MajorJoint::kRightToe)};
  double sum = 0;
  int legs = 0;
  for (const LegColumns& leg : rig.legs) {
    if (!leg.usable()) continue;
    sum += lengths[leg.knee] + lengths[leg.ankle];
    ++legs;
  }
  rig.leg_length = legs > 0 ? sum / legs : 0.0;
  rig.body_height = standing_height(majors, lengths);
  return rig;
}

Eigen::MatrixXd detect_foot_contacts(const Eigen::MatrixXd& world, const FootRig& rig) {
  check_columns(world, rig, "foot contacts");
  const Eigen::Index frames = world.rows();
  Eigen::MatrixXd contacts = Eigen::MatrixXd::Zero(frames, 2);
  if (frames == 0) return contacts;
  const FootContactOptions& o = rig.options;
  const double max_height = o.height_fraction * rig.leg_length;
  const double max_speed = o.speed_fraction * rig.leg_length;
  std::vector<double> heights(static_cast<size_t>(frames));
  std::vector<char> planted(static_cast<size_t>(frames));
  for (int side = 0; side < 2; ++side) {
    const LegColumns& leg = rig.legs[side];
    if (!leg.usable()) continue;
    for (Eigen::Index t = 0; t < frames; ++t) heights[t] = world(t, 3 * leg.ankle + 1);
    // The floor under this foot: a low percentile of the ankle's own height, so a take whose
    // ground is not at 0 (or a skeleton whose ankle is high above its sole) needs no setting.
    std::vector<double> sorted = heights;
    const size_t k = static_cast<size_t>(kFloorPercentile * static_cast<double>(frames - 1));
    std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
    const double floor = sorted[k];
    for (Eigen::Index t = 0; t < frames; ++t) {
      // Central differences (one-sided at the ends): the speed at the frame itself.
      const Eigen::Index t0 = std::max<Eigen::Index>(0, t - 1), t1 = std::min(frames - 1, t + 1);
      const double speed =
          t1 > t0 ? (joint_at(world, t1, leg.ankle) - joint_at(world, t0, leg.ankle)).norm() * rig.fps / (t1 - t0)
                  : 0.0;
      planted[t] = heights[t] - floor <= max_height && speed <= max_speed;
    }
    for (Eigen::Index t = 0; t < frames; ++t) contacts(t, side) = planted[t] ? 1.0 : 0.0;
  }
  tidy_contacts(contacts, rig);
  return contacts;
}

void tidy_contacts(Eigen::MatrixXd& contacts, const FootRig& rig) {
  const FootContactOptions& o = rig.options;
  const int max_gap = seconds_to_frames(o.max_gap_seconds, rig.fps);
  const int min_run = std::max(1, static_cast<int>(std::ceil(o.min_contact_seconds * rig.fps - kTimeEpsilon)));
  const Eigen::Index frames = contacts.rows();
  for (Eigen::Index side = 0; side < contacts.cols(); ++side) {
    auto planted = contacts.col(side);
    // Fill short breaks between two contacts, then drop contacts too short to be steps.
    for (Eigen::Index t = 0; t < frames;) {
      if (planted[t] > 0.5) {
        ++t;
        continue;
      }
      Eigen::Index e = t;
      while (e < frames && !(planted[e] > 0.5)) ++e;
      if (t > 0 && e < frames && e - t <= max_gap) planted.segment(t, e - t).setOnes();
      t = e;
    }
    for (Eigen::Index t = 0; t < frames;) {
      if (!(planted[t] > 0.5)) {
        ++t;
        continue;
      }
      Eigen::Index e = t;
      while (e < frames && planted[e] > 0.5) ++e;
      if (e - t < min_run) planted.segment(t, e - t).setZero();
      t = e;
    }
  }
}

Eigen::MatrixXd carry_contacts(const Eigen::MatrixXd& contacts_b, const Eigen::VectorXd& warp) {
  if (contacts_b.rows() == 0 || contacts_b.cols() != 2)
    throw InputError("foot contacts: expected B's contacts as frames x 2, found " +
                     std::to_string(contacts_b.rows()) + " x " + std::to_string(contacts_b.cols()));
  const Eigen::Index last = contacts_b.rows() - 1;
  Eigen::MatrixXd out(warp.size(), 2);
  for (Eigen::Index i = 0; i < warp.size(); ++i) {
    const double j = std::isfinite(warp[i]) ? std::round(warp[i]) : 0.0;
    out.row(i) = contacts_b.row(static_cast<Eigen::Index>(std::clamp(j, 0.0, static_cast<double>(last))));
  }
  return out;
}

void blend_contacts(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double alpha, Eigen::MatrixXd& out) {
  if (a.rows() != b.rows() || a.cols() != 2 || b.cols() != 2)
    throw InputError("foot contacts: expected two F x 2 contact matrices, found " + std::to_string(a.rows()) +
                     " x " + std::to_string(a.cols()) + " and " + std::to_string(b.rows()) + " x " +
                     std::to_string(b.cols()));
  out.resize(a.rows(), 2);
  for (Eigen::Index t = 0; t < a.rows(); ++t)
    for (int s = 0; s < 2; ++s) out(t, s) = (1.0 - alpha) * a(t, s) + alpha * b(t, s) > 0.5 ? 1.0 : 0.0;
}

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
  if (!(distance > kStraightLeg * (thigh + shin))) {  // target on the hip: no direction to reach
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
  if (bend.norm() <= kStraightLeg * (thigh + shin)) bend = bend_fallback - n * n.dot(bend_fallback);
  bend = bend.norm() > 0 ? Eigen::Vector3d(bend.normalized()) : any_perpendicular(n);
  const double along = (thigh * thigh - shin * shin + reach * reach) / (2.0 * reach);
  const double across = std::sqrt(std::max(0.0, thigh * thigh - along * along));
  *new_knee = hip + n * along + bend * across;
  *new_ankle = hip + n * reach;
}

void apply_foot_lock(Eigen::MatrixXd& world, const Eigen::MatrixXd& contacts, const FootRig& rig,
                     FootLockScratch& scratch, const Eigen::MatrixXd* drift) {
  if (drift != nullptr && (drift->rows() != world.rows() || drift->cols() != 4))
    throw InputError("foot lock: expected the planted feet's drift as " + std::to_string(world.rows()) + " x 4");
  check_columns(world, rig, "foot lock");
  check_contacts(world, contacts, "foot lock");
  const Eigen::Index frames = world.rows();
  const int ramp = rig.blend_frames();
  scratch.weight.resize(frames);
  scratch.target.resize(frames, 2);
  for (int side = 0; side < 2; ++side) {
    const LegColumns& leg = rig.legs[side];
    if (!leg.usable()) continue;
    scratch.weight.setZero();  // 1 where the ankle gets an offset, 0 where it is left alone
    scratch.target.setZero();  // the horizontal offset (x, z) that takes the ankle to its target
    // Each contact run pins the ankle at its mean horizontal position (the least total
    // correction) for the whole run: no sliding while planted. The offsets that takes then
    // differ from one run to the next; between them, the change is spread over the whole swing
    // (smoothstep), which adds little to the swinging foot's speed, where a fade of a few frames
    // at landing or lift-off would add it all at the foot's fastest moments. Before the first
    // run and after the last the offset fades in and out over blend_frames().
    Eigen::Index previous_end = -1;  // last frame of the previous run
    for (Eigen::Index t = 0; t < frames;) {
      if (contacts(t, side) <= 0.5) {
        ++t;
        continue;
      }
      const Eigen::Index start = t;
      // The drift expected so far in the run (none without `drift`): the target moves with it.
      double x = 0, z = 0, ex = 0, ez = 0;
      for (; t < frames && contacts(t, side) > 0.5; ++t) {
        x += world(t, 3 * leg.ankle) - ex;
        z += world(t, 3 * leg.ankle + 2) - ez;
        if (drift != nullptr) {
          ex += (*drift)(t, 2 * side);
          ez += (*drift)(t, 2 * side + 1);
        }
      }
      const Eigen::Index end = t - 1;
      const double n = static_cast<double>(end - start + 1);
      x /= n;
      z /= n;
      ex = ez = 0;
      for (Eigen::Index u = start; u <= end; ++u) {
        scratch.weight[u] = 1.0;
        scratch.target(u, 0) = x + ex - world(u, 3 * leg.ankle);
        scratch.target(u, 1) = z + ez - world(u, 3 * leg.ankle + 2);
        if (drift != nullptr) {
          ex += (*drift)(u, 2 * side);
          ez += (*drift)(u, 2 * side + 1);
        }
      }
      if (previous_end >= 0) {  // the swing from the previous run
        const Eigen::Index span = start - previous_end;
        for (Eigen::Index u = previous_end + 1; u < start; ++u) {
          const double f = smoothstep(static_cast<double>(u - previous_end) / span);
          scratch.weight[u] = 1.0;
          scratch.target.row(u) = (1.0 - f) * scratch.target.row(previous_end) + f * scratch.target.row(start);
        }
      } else {  // fade in before the first run
        for (Eigen::Index u = std::max<Eigen::Index>(0, start - ramp); u < start; ++u) {
          const double f = smoothstep(1.0 - static_cast<double>(start - u) / (ramp + 1));
          scratch.weight[u] = 1.0;
          scratch.target.row(u) = f * scratch.target.row(start);
        }
      }
      previous_end = end;
    }
    if (previous_end >= 0)  // fade out after the last run
      for (Eigen::Index u = previous_end + 1; u <= std::min(frames - 1, previous_end + ramp); ++u) {
        const double f = smoothstep(1.0 - static_cast<double>(u - previous_end) / (ramp + 1));
        scratch.weight[u] = 1.0;
        scratch.target.row(u) = f * scratch.target.row(previous_end);
      }
    // The knee's bend direction where the leg is straight: the last frame's, within a second,
    // where it was not (none: two_bone_ik picks one).
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
    for (Eigen::Index t = 0; t < frames; ++t) {
      if (scratch.weight[t] <= 0.0) continue;
      const Eigen::Vector3d hip = joint_at(world, t, leg.hip);
      const Eigen::Vector3d knee = joint_at(world, t, leg.knee);
      const Eigen::Vector3d ankle = joint_at(world, t, leg.ankle);
      // The offset, shortened where it would take the ankle out of the leg's reach: the IK would
      // then lift the ankle along the straightened leg and let the knee snap back when the lock
      // lets go. What is left of the slide stays (the leg cannot reach further).
      const Eigen::Vector2d offset(scratch.target(t, 0), scratch.target(t, 1));
      // (A leg already straighter than that may stay as straight.)
      const double reach = std::max(kReachMargin * ((knee - hip).norm() + (ankle - knee).norm()), (ankle - hip).norm());
      Eigen::Vector3d target = ankle + Eigen::Vector3d(offset.x(), 0.0, offset.y());
      if ((target - hip).norm() > reach) {
        // |ankle - hip + f (ox, 0, oz)| = reach: the positive root f, within [0, 1].
        const Eigen::Vector3d d = ankle - hip, o(offset.x(), 0.0, offset.y());
        const double a = o.squaredNorm(), b = 2.0 * d.dot(o), c = d.squaredNorm() - reach * reach;
        const double disc = b * b - 4.0 * a * c;
        const double f = a > 0 && disc >= 0 ? std::clamp((-b + std::sqrt(disc)) / (2.0 * a), 0.0, 1.0) : 0.0;
        target = ankle + f * o;
      }
      Eigen::Vector3d new_knee, new_ankle;
      // The knee's bend direction (the IK's pole) is taken from the leg's own pose, the knee's
      // offset from its hip-ankle line, with a slight bias towards where the foot points. Taken
      // from the hip-target line instead, it would swing round whenever the lock pulls the ankle
      // across the knee's plane, and a knee that the blend leaves nearly straight would fold
      // backwards; the bias keeps the pole from passing through zero as the leg straightens.
      Eigen::Vector3d pole;
      {
        const Eigen::Vector3d leg_line = ankle - hip;
        const double len2 = leg_line.squaredNorm();
        pole = knee - hip;
        if (len2 > 0) pole -= leg_line * (leg_line.dot(knee - hip) / len2);
        // The bias fades out as the knee bends more (gone at three times its size) and as the
        // ankle moves less (gone where it stays), so a lock that does not move the ankle leaves
        // the leg as it was, and a bent knee keeps its own plane.
        const double moved = std::hypot(scratch.target(t, 0), scratch.target(t, 1));
        const double bias = std::clamp(1.0 - pole.norm() / (3.0 * kKneeForwardBias * rig.leg_length), 0.0, 1.0) *
                            std::clamp(moved / (kKneeBiasMove * rig.leg_length), 0.0, 1.0);
        if (leg.toe >= 0 && bias > 0.0) {
          Eigen::Vector3d forward = joint_at(world, t, leg.toe) - ankle;
          forward.y() = 0.0;
          if (forward.norm() > 0) pole += bias * kKneeForwardBias * rig.leg_length * forward.normalized();
        }
      }
      const bool straight = !(pole.norm() > kStraightLeg * rig.leg_length);
      two_bone_ik_pole(hip, knee, ankle, target, straight ? last_bend(t) : pole,
                       straight ? last_bend(t) : Eigen::Vector3d::Zero(), &new_knee, &new_ankle);
      set_joint(world, t, leg.knee, new_knee);
      set_joint(world, t, leg.ankle, new_ankle);
      if (leg.toe >= 0) set_joint(world, t, leg.toe, joint_at(world, t, leg.toe) + (new_ankle - ankle));
    }
  }
}

}  // namespace mostyle
