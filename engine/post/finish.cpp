#include "engine/post/finish.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "engine/kinematics/limb_length.h"
#include "engine/measure/fastest_joint.h"
#include "engine/measure/planted_feet.h"
#include "engine/prepare/canonical_frame.h"
#include "engine/prepare/root_path.h"

namespace mostyle {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Rows of x at fractional rows u, nearest row (for 0/1 contacts).
void nearest_rows(const Eigen::MatrixXd& x, const Eigen::VectorXd& u, Eigen::MatrixXd& out) {
  out.resize(u.size(), x.cols());
  const double last = static_cast<double>(x.rows() - 1);
  for (Eigen::Index k = 0; k < u.size(); ++k)
    out.row(k) = x.row(static_cast<Eigen::Index>(std::lround(std::clamp(u[k], 0.0, last))));
}

// The loop cut when asked (options.closed: all but the last frame; options.loop: find_loop's),
// closed at the seam: local, u, the ground (s.ground), heading (s.heading) and out.contacts cut
// to its frames; the headings before the cut kept (s.heading_uncut) for the body drift.
void cut_loop(const FinishOptions& options, Eigen::MatrixXd& local, Eigen::VectorXd& u, FinishScratch& s,
              FinishedMotion& out) {
  out.loop = LoopCut();
  if (options.closed && u.size() >= 3) {
    out.loop.begin = 0;
    out.loop.end = static_cast<int>(u.size()) - 1;
    out.loop.cycles = 1;
  } else if (options.loop) {
    out.loop = find_loop(out.contacts, local, s.heading);
  }
  if (out.loop.frames() > 0) {
    s.heading_uncut = s.heading;
    close_loop(out.loop, local, s.ground, s.heading, out.contacts);
    u = u.segment(out.loop.begin, out.loop.frames()).eval();
  }
}

// The body drift (K x 2 kFootJoints, before any loop cut) into the world by the heading at each
// output frame (s.drift), cut to the loop's frames where a loop was cut.
void world_drift(const Eigen::MatrixXd& body_drift, const LoopCut& loop, FinishScratch& s) {
  const Eigen::VectorXd& heading = loop.frames() > 0 ? s.heading_uncut : s.heading;
  s.drift.resize(body_drift.rows(), 2 * kFootJoints);
  for (Eigen::Index k = 0; k < body_drift.rows(); ++k) {
    const double c = std::cos(heading[k]), sn = std::sin(heading[k]);
    for (int j = 0; j < kFootJoints; ++j) {
      const double bx = body_drift(k, 2 * j), bz = body_drift(k, 2 * j + 1);
      s.drift(k, 2 * j) = c * bx + sn * bz;
      s.drift(k, 2 * j + 1) = -sn * bx + c * bz;
    }
  }
  if (loop.frames() > 0) s.drift = s.drift.middleRows(loop.begin, loop.frames()).eval();
}

// held (K x kFootJoints) cleared where the takes' planted drift (K x 2 kFootJoints, a frame's
// move to the next) moves that joint more than `step` into or out of the frame. O(K).
void release_moving_feet(const Eigen::MatrixXd& drift, double step, Eigen::MatrixXd& held) {
  const Eigen::Index frames = std::min(drift.rows(), held.rows());
  auto moved = [&](Eigen::Index t, int j) { return std::hypot(drift(t, 2 * j), drift(t, 2 * j + 1)) > step; };
  for (Eigen::Index t = 0; t < frames; ++t)
    for (int j = 0; j < kFootJoints; ++j)
      if (held(t, j) > 0.5 && (moved(t, j) || (t > 0 && moved(t - 1, j)))) held(t, j) = 0.0;
}

LimbLengthOptions limb_options(const FinishRig& rig) {
  LimbLengthOptions limbs;
  limbs.short_fraction = rig.short_bone_fraction;
  return limbs;
}

// The speed limit (speed_limit.h) at kSpeedLimitOverTakes times the takes' fastest joint, the
// limb lengths held after it when they are asked for.
void limit_speed(const FinishRig& rig, const FinishOptions& options, FinishScratch& s, Eigen::MatrixXd& world) {
  if (!(rig.lock_limits.fastest_joint > 0.0)) return;
  const double limit = kSpeedLimitOverTakes * rig.lock_limits.fastest_joint;
  if (options.limb_lengths)
    limit_joint_speed_keeping_bones(world, rig.feet->fps, limit, *rig.parents, *rig.lengths, limb_options(rig), s.speed);
  else
    limit_joint_speed(world, rig.feet->fps, limit, s.speed);
}

// The lock reads a loop as a take with two ends: what it moves at the last frame and at the
// first differ, a jump at the seam. That difference is taken up over the loop so the last frame
// is moved as the first is and leads into it as any frame into the next. Spread evenly over the
// loop, it would slide the planted feet with it, so a leg takes its share over its swings
// instead, where its foot moves anyway (each swing's steps weighted by a bump that starts and
// ends at zero: no jump in speed at lift-off or landing), as much of it as keeps the leg's
// joints under `limit` (units per frame; no faster than they were where they already were), the
// rest evenly. Joints of no leg, and a leg that never swings, take it evenly. s.before_lock: the
// world before the lock.
// Test: the Mixamo loop of "palette: planted feet of a mix and a transfer move as their takes' do" (mix_palette_test.cpp).
void close_locked_seam(const FootRig& feet, double limit, FinishScratch& s, Eigen::MatrixXd& world) {
  const Eigen::Index k = world.rows();
  const Eigen::RowVectorXd gap = (world.row(0) - s.before_lock.row(0)) - (world.row(k - 1) - s.before_lock.row(k - 1));
  planted_frames(world, feet, s.planted, s.heights);
  const std::array<int, kFootJoints> columns = foot_joint_columns(feet);
  auto even = [&](Eigen::Index f) { return double(f) / double(k - 1); };
  std::vector<char> on_leg(world.cols() / 3, 0);
  s.seam_share.resize(k);
  for (int side = 0; side < 2; ++side) {
    const LegColumns& leg = feet.legs[side];
    if (!leg.usable()) continue;
    const std::array<int, 3> joints = {leg.knee, leg.ankle, leg.toe};
    for (int c : joints)
      if (c >= 0) on_leg[c] = 1;
    // A step f - 1 -> f swings where no planted joint of the foot holds it at both ends.
    auto swinging = [&](Eigen::Index f) {
      for (int j = 2 * side; j < 2 * side + 2; ++j)
        if (columns[j] >= 0 && s.planted(f - 1, j) > 0.0 && s.planted(f, j) > 0.0) return false;
      return true;
    };
    s.seam_share.setZero();
    for (Eigen::Index f = 1; f < k;) {
      if (!swinging(f)) { ++f; continue; }
      Eigen::Index end = f;
      while (end < k && swinging(end)) ++end;
      const double n = double(end - f);
      for (Eigen::Index g = f; g < end; ++g) s.seam_share[g] = std::pow(std::sin(kPi * (double(g - f) + 0.5) / n), 2);
      f = end;
    }
    const double total = s.seam_share.sum();
    if (total > 0.0) {
      for (Eigen::Index f = 1; f < k; ++f) s.seam_share[f] = s.seam_share[f - 1] + s.seam_share[f] / total;
    }
    s.seam_share[0] = 0.0;
    // The step of joint c into frame f with `swing` of the share over the swings, the rest even.
    auto step = [&](int c, Eigen::Index f, double swing) {
      const double moved = swing * (s.seam_share[f] - s.seam_share[f - 1]) + (1.0 - swing) / double(k - 1);
      return (world.block(f, 3 * c, 1, 3) - world.block(f - 1, 3 * c, 1, 3) + moved * gap.segment(3 * c, 3)).norm();
    };
    auto fits = [&](double swing) {
      for (Eigen::Index f = 1; f < k; ++f)
        for (int c : joints)
          if (c >= 0 && step(c, f, swing) > std::max(limit, step(c, f, 0.0)) + 1e-12) return false;
      return true;
    };
    double swing = 0.0;
    if (total > 0.0) {
      if (!(limit > 0.0) || fits(1.0)) {
        swing = 1.0;
      } else {
        double lo = 0.0, hi = 1.0;
        for (int i = 0; i < 20; ++i) (fits(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
        swing = lo;
      }
    }
    for (Eigen::Index f = 1; f < k; ++f) {
      const double share = swing * s.seam_share[f] + (1.0 - swing) * even(f);
      for (int c : joints)
        if (c >= 0) world.block(f, 3 * c, 1, 3) += share * gap.segment(3 * c, 3);
    }
  }
  for (Eigen::Index c = 0; c < Eigen::Index(on_leg.size()); ++c) {
    if (on_leg[c]) continue;
    for (Eigen::Index f = 1; f < k; ++f) world.block(f, 3 * c, 1, 3) += even(f) * gap.segment(3 * c, 3);
  }
}

}  // namespace

void finish_preview(const FinishPath& path, const FinishRig& rig, const FinishOptions& options, Eigen::MatrixXd& local,
                    Eigen::VectorXd& u, FinishScratch& s, FinishedMotion& out) {
  const RowSampler& sampler = *path.sampler;
  const Eigen::VectorXd& heading_u = *path.heading_u;
  sampler.apply(*path.ground_u, s.ground);
  s.heading.resize(u.size());
  // Headings along the shorter arc between samples: where the mixed turns carry a whole turn
  // (match_turns), a plain interpolation would spin the body round within one frame.
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    const int i = sampler.row[k];
    const double h0 = heading_u[i];
    const double h1 = heading_u.size() > 1 ? heading_u[i + 1] : h0;
    s.heading[k] = h0 + sampler.frac[k] * std::remainder(h1 - h0, 2.0 * kPi);
  }
  nearest_rows(*path.contacts_u, u, out.contacts);
  tidy_contacts(out.contacts, *rig.feet);
  cut_loop(options, local, u, s, out);
  to_world(local, s.ground, s.heading, &out.world);
  out.foot_sliding_raw = out.foot_sliding_cleaned = out.limb_length_max_error = out.fastest_joint = 0.0;
  if (options.limb_lengths) apply_limb_lengths(out.world, *rig.parents, *rig.lengths, limb_options(rig));
}

void finish_rest(const FinishRig& rig, const FinishOptions& options, FinishScratch& s, FinishedMotion& out,
                 const Eigen::MatrixXd* body_drift, const Eigen::MatrixXd* feet_height) {
  if (body_drift != nullptr) world_drift(*body_drift, out.loop, s);
  // No pops: no joint faster than the takes' fastest allows.
  limit_speed(rig, options, s, out.world);
  // Foot lock (beyond the paper): planted ankles pinned by two-bone IK, which keeps bone lengths.
  planted_frames(out.world, *rig.feet, s.planted, s.heights);
  out.foot_sliding_raw = planted_speed(out.world, s.planted, *rig.feet).speed;
  out.foot_sliding_cleaned = out.foot_sliding_raw;
  if (options.foot_lock) {
    const bool looped = out.loop.frames() > 1;
    if (looped) s.before_lock = out.world;
    // Feet the takes hold in the air lifted out of the planted band first, and the feet they
    // plant pinned with the output's own planted feet: the lock then pins the steps the takes
    // plant, not a swing that skims the floor.
    if (feet_height != nullptr) {
      if (out.loop.frames() > 0) s.feet_height = feet_height->middleRows(out.loop.begin, out.loop.frames());
      else s.feet_height = *feet_height;
      s.air = (s.feet_height.array() > kSwingAirBands).cast<double>();
      s.held = (s.feet_height.array() <= 1.0).cast<double>();
      if (body_drift != nullptr) release_moving_feet(s.drift, kHeldFootSpeed * rig.feet->body_height / rig.feet->fps, s.held);
      // Not a loop: closing its seam blends its last frames towards its first, so there the
      // takes' heights at the frames shown do not describe the output's feet (a foot eased down
      // towards its first frame's step would be lifted against the seam, and the lift spread
      // over the whole loop with the lock's).
      if (out.loop.frames() == 0) {
        lift_swinging_feet(out.world, *rig.feet, s.air, s.swing);
        settle_held_feet(out.world, *rig.feet, s.feet_height, s.held, s.swing);
      }
    }
    apply_foot_lock(out.world, *rig.feet, s.foot, body_drift != nullptr ? &s.drift : nullptr, rig.lock_limits,
                    feet_height != nullptr ? &s.held : nullptr);
    // The lift and the lock bend knees; where that moves one faster than the limit (a knee
    // turning its bend in a frame), the speed limit spreads it as it did the mix's.
    limit_speed(rig, options, s, out.world);
    // The lock reads the loop as a take with two ends: what it moves at the last frame and at the
    // first differ, a jump at the seam. That difference is spread over the loop, so the last frame
    // is moved as the first is and leads into it as any frame into the next.
    if (looped) close_locked_seam(*rig.feet, kSpeedLimitOverTakes * rig.lock_limits.fastest_joint / rig.feet->fps, s, out.world);
    planted_frames(out.world, *rig.feet, s.planted, s.heights);
    out.foot_sliding_cleaned = planted_speed(out.world, s.planted, *rig.feet).speed;
  }
  out.limb_length_max_error = max_bone_length_error(out.world, *rig.parents, *rig.lengths);
  out.fastest_joint = fastest_joint_speed(out.world, rig.feet->fps, s.steps);
}

}  // namespace mostyle
