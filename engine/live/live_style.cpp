#include "engine/live/live_style.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "engine/export/export_solve.h"
#include "engine/base/error.h"
#include "engine/kinematics/ease.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/limb_length.h"
#include "engine/kinematics/two_bone_ik.h"
#include "engine/live/live_feet.h"
#include "engine/live/live_phase.h"
#include "engine/live/style_change.h"
#include "engine/measure/foot_contact.h"
#include "engine/measure/planted_feet.h"
#include "engine/prepare/major_skeleton.h"
#include "engine/prepare/major_take.h"
#include "engine/synthesize/mix_palette.h"
#include "engine/align/prepare_takes.h"

namespace mostyle {
namespace {

constexpr double kMaxFps = 1000.0;
// No joint's change moves more than this share of the stream's fastest joint step lately from
// one frame to the next: a styled joint then moves at most 1 + this times as fast as the
// stream's fastest.
constexpr double kChangeSpeedShare = 0.2;
// The stream's fastest joint step is remembered with this half-life, so that one glitch (a jump
// of the capture) loosens the speed limit for a while, not for good.
constexpr double kFastestHalfLifeSeconds = 10.0;
// Where a foot lands away from where its swing was taking it (a strike sooner or later than the
// phase said), the difference closes over this time after the landing.
constexpr double kLandingSettleSeconds = 0.15;
// A foot joint is never nearer its floor than the stream's is to its own, up to this share of
// the body's height: twice the band the planted-feet measure calls planted (planted_feet.h), so
// that a style whose swings skim the floor does not glide a foot along it where the stream lifts
// it, and no foot goes below the floor.
constexpr double kSwingClearance = 2.0 * kPlantedHeightFraction;
// The first frame tells the up axis when the head stands this share of the body's height above
// the ankles along it, and along it more than along the other two together.
constexpr double kUpAxisShare = 0.5;
constexpr double kDegenerateAxis = 1e-12;  // squared hip-axis length on the ground
// A frame whose strengths are all 0 and whose joints the change moves less than this share of
// the body's height is the stream's own frame, copied through.
constexpr double kUnchanged = 1e-9;

// (x, z) turned into the body's frame at heading h (canonical_frame.h: R_y(-h)), and back.
inline void to_body(double h_cos, double h_sin, double dx, double dz, double* x, double* z) {
  *x = h_cos * dx - h_sin * dz;
  *z = h_sin * dx + h_cos * dz;
}
inline void from_body(double h_cos, double h_sin, double x, double z, double* dx, double* dz) {
  *dx = h_cos * x + h_sin * z;
  *dz = -h_sin * x + h_cos * z;
}

inline Eigen::Vector3d at(const Eigen::VectorXd& v, int column) { return v.segment<3>(3 * column); }

// One foot joint (ankle or toe) under the lock: world offsets from the stream's joint.
struct FootJointLock {
  int column = -1;
  Eigen::Vector3d settle = Eigen::Vector3d::Zero();  // at the landing: where the joint was against the hold
  Eigen::Vector3d lift = Eigen::Vector3d::Zero();    // at the lift: the lock's correction then
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // this frame's offset
};

// A foot is planted for the lock while its ankle or its toe is (LiveFeet of each): from the heel
// strike, or the toe's in a run, to the toe-off, so that a foot rolling onto its toe pivots as the
// stream's does.
struct LegLock {
  std::array<FootJointLock, 2> joints;  // ankle, toe (column -1 where the rig has none)
  // Per style, at strength 1: the offset both joints are held at while planted (the ankle's
  // change over the neutral's stance, set at the landing: the planted foot is moved whole).
  std::vector<Eigen::Vector3d> hold;
  bool planted = false;
  long landed = -1, lifted = -1;  // the frames its landing and its lift were seen
  long strike = -1, lift = -1;    // the frames they happened (seen a few frames late)
  double last_swing = 0.0;        // the stream's last swing of this foot, frames (0: none yet)
  double swing_frames = 1.0;      // how long its swing is expected to last from `lifted`
};

void check_spec(const LiveStyleSpec& spec, double fps) {
  if (!(fps > 0.0) || fps > kMaxFps)
    throw InputError("live: expected a stream frame rate above 0 and up to 1000 frames per second, found " +
                     std::to_string(fps));
  const size_t n = spec.takes.size();
  if (n < 2 || n > static_cast<size_t>(kMaxPaletteTakes))
    throw InputError("live: expected a neutral take and 1 to " + std::to_string(kMaxPaletteTakes - 1) +
                     " style takes, found " + std::to_string(n) + " takes");
  for (const auto& t : spec.takes)
    if (t == nullptr) throw InputError("live: a take was not loaded");
}

void check_strengths(const std::vector<double>& strengths, size_t styles) {
  if (strengths.size() != styles)
    throw InputError("live: expected " + std::to_string(styles) + " strengths, one per style, found " +
                     std::to_string(strengths.size()));
  for (double s : strengths)
    if (!std::isfinite(s) || s < kMinStrength || s > kMaxStrength)
      throw InputError("live: expected a strength from -1 to 2, found " + std::to_string(s));
}


}  // namespace

struct LiveStyle::State {
  State(const LiveFeet& f, const LivePhase& p, ExportFrameSolver&& s)
      : feet(f), toes(f), phase(p), fresh_feet(f), fresh_phase(p), solver(std::move(s)) {}

  Skeleton skeleton;
  double fps = 30.0;
  std::vector<int> majors, parents, joints;  // canonical joints (M), parents within them, the stream's joints
  FootRig rig;
  double body_height = 0.0;
  StyleChange change;
  std::vector<int> chain;                    // the stream's joints posed, parents first
  Pose posed;                                // per stream joint, global, the stream's axes (chain's only)
  Eigen::Matrix3d up = Eigen::Matrix3d::Identity();  // the stream's axes to Y up
  // This frame, Y up, 3M values each.
  Eigen::VectorXd in, previous_in, local, change_local, raw, target, delta, previous_delta, solve_targets;
  Eigen::Vector2d ground = Eigen::Vector2d::Zero();
  double heading = 0.0, heading_cos = 1.0, heading_sin = 0.0;
  int phase_row = 0, next_phase_row = 0;  // the change tables' rows this frame's phase lies between
  double phase_fraction = 0.0;            // and how far towards the second
  bool has_heading = false;
  LiveFeet feet;  // the ankles' contacts: the gait's strikes, and the lock's
  LiveFeet toes;  // the toes' (the ankles again on a leg without one): the lock's
  LivePhase phase;
  const LiveFeet fresh_feet;    // feet, toes and phase as a stream's first frame finds them
  const LivePhase fresh_phase;
  std::vector<double> from, to, eased;  // strengths: the ease's start and end, and where it is
  double ease = 1.0;                    // its progress, 0 to 1
  std::array<LegLock, 2> legs;
  double fastest = 0.0;                 // the stream's fastest joint step lately, file units per frame
  double fastest_decay = 1.0;           // per frame: kFastestHalfLifeSeconds at fps
  std::vector<double> last_out;         // the frame before's output (held over a frame that is not numbers)
  long frames = 0;
  bool copied = false;                  // the frame before was copied through
  ExportFrameSolver solver;

  void start_stream();
  void pose(const double* values);
  void read_up_axis();
  void to_canonical();
  void track_gait();
  void ease_strengths();
  void change_at_phase();
  void place_targets();
  Eigen::Vector3d joint_change(int style, int column, bool stance_mean, int side) const;
  void lock_feet();
  void plant_leg(LegLock& leg, int side, bool* struck, bool* lifted);
  double lowest(const LegLock& leg, int column, double floor) const;
  void lock_joint(LegLock& leg, FootJointLock& joint, int side, bool struck, bool lifted,
                  const Eigen::Vector3d& stance);
  void limit_speed();
  void solve(const double* values, double* out);
};

// Everything a stream's frames build up, as before its first frame; the strengths at their
// targets, the ease done.
void LiveStyle::State::start_stream() {
  const Eigen::Index n = 3 * static_cast<Eigen::Index>(joints.size());
  for (Eigen::VectorXd* v : {&in, &previous_in, &local, &change_local, &raw, &target, &delta, &previous_delta,
                             &solve_targets})
    v->setZero(n);
  up.setIdentity();
  ground.setZero();
  heading = 0.0;
  heading_cos = 1.0;
  heading_sin = 0.0;
  phase_row = next_phase_row = 0;
  phase_fraction = 0.0;
  has_heading = false;
  feet = fresh_feet;
  toes = fresh_feet;
  phase = fresh_phase;
  from = eased = to;
  ease = 1.0;
  for (size_t side = 0; side < 2; ++side) {
    LegLock fresh;
    fresh.joints[0].column = rig.legs[side].ankle;
    fresh.joints[1].column = rig.legs[side].toe;
    fresh.hold.assign(to.size(), Eigen::Vector3d::Zero());
    legs[side] = std::move(fresh);
  }
  fastest = 0.0;
  last_out.assign(static_cast<size_t>(skeleton.channel_count), 0.0);
  frames = 0;
  copied = false;
  solver.restart();
}

// FK of the joints posed, in the stream's axes, then the major joints turned to Y up.
void LiveStyle::State::pose(const double* values) {
  pose_frame(skeleton, values, chain, &posed);
  if (frames == 0) read_up_axis();
  for (size_t c = 0; c < joints.size(); ++c)
    in.segment<3>(3 * static_cast<Eigen::Index>(c)) = up * posed.positions[static_cast<size_t>(joints[c])];
}

// The up axis from the first frame: the one the head (else the highest trunk joint) stands
// above the ankles along, clearly; Y when the frame does not tell.
void LiveStyle::State::read_up_axis() {
  int top = -1;
  for (MajorJoint m : {MajorJoint::kHead, MajorJoint::kChest, MajorJoint::kSpine}) {
    top = major_column(majors, static_cast<int>(m));
    if (top >= 0) break;
  }
  const int left = rig.legs[0].ankle, right = rig.legs[1].ankle;
  if (top < 0 || left < 0 || right < 0) return;
  const std::vector<Eigen::Vector3d>& position = posed.positions;
  const Eigen::Vector3d v = position[static_cast<size_t>(joints[static_cast<size_t>(top)])] -
                            0.5 * (position[static_cast<size_t>(joints[static_cast<size_t>(left)])] +
                                   position[static_cast<size_t>(joints[static_cast<size_t>(right)])]);
  Eigen::Index axis = 0;
  const double along = v.cwiseAbs().maxCoeff(&axis);
  if (along < kUpAxisShare * body_height || along < v.cwiseAbs().sum() - along) return;
  Eigen::Vector3d from = Eigen::Vector3d::Zero();
  from[axis] = v[axis] > 0 ? 1.0 : -1.0;
  up = Eigen::Quaterniond::FromTwoVectors(from, Eigen::Vector3d::UnitY()).toRotationMatrix();
}

// canonical_frame.h, one frame: the heading from the hips' left-right axis (unwrapped against
// the frame before), the hips' ground point, the pose relative to both.
void LiveStyle::State::to_canonical() {
  const int lh = rig.legs[0].hip, rh = rig.legs[1].hip;
  const double rx = in[3 * lh] - in[3 * rh], rz = in[3 * lh + 2] - in[3 * rh + 2];
  if (rx * rx + rz * rz > kDegenerateAxis) {
    double h = std::atan2(-rz, rx);
    if (has_heading) h += 2 * M_PI * std::round((heading - h) / (2 * M_PI));
    heading = h;
    has_heading = true;
  }
  heading_cos = std::cos(heading);
  heading_sin = std::sin(heading);
  ground = Eigen::Vector2d(in[0], in[2]);
  for (Eigen::Index j = 0; j < static_cast<Eigen::Index>(joints.size()); ++j) {
    to_body(heading_cos, heading_sin, in[3 * j] - ground.x(), in[3 * j + 2] - ground.y(), &local[3 * j], &local[3 * j + 2]);
    local[3 * j + 1] = in[3 * j + 1];
  }
}

void LiveStyle::State::track_gait() {
  const int la = rig.legs[0].ankle, ra = rig.legs[1].ankle;
  feet.update(at(in, la), at(in, ra));
  const int lt = rig.legs[0].toe, rt = rig.legs[1].toe;
  toes.update(at(in, lt >= 0 ? lt : la), at(in, rt >= 0 ? rt : ra));
  std::array<long, 2> strikes{{-1, -1}};
  for (size_t side = 0; side < 2; ++side)
    if (feet.foot(static_cast<int>(side)).struck_now) strikes[side] = feet.foot(static_cast<int>(side)).strike;
  phase.update(strikes, {Eigen::Vector2d(local[3 * la], local[3 * la + 2]), Eigen::Vector2d(local[3 * ra], local[3 * ra + 2])});
  // The fastest joint step lately (not the first frame's: nothing before it).
  if (frames > 0) {
    fastest *= fastest_decay;
    for (Eigen::Index j = 0; j < static_cast<Eigen::Index>(joints.size()); ++j)
      fastest = std::max(fastest, (in.segment<3>(3 * j) - previous_in.segment<3>(3 * j)).norm());
  }
  previous_in = in;
}

void LiveStyle::State::ease_strengths() {
  ease = std::min(1.0, ease + 1.0 / std::max(1.0, kLiveStrengthEaseSeconds * fps));
  const double w = smoothstep(ease);
  for (size_t i = 0; i < eased.size(); ++i) eased[i] = from[i] + (to[i] - from[i]) * w;
}

// Strength x change at this frame's phase: the cycle's change (linear between the table's
// phases) and the posture change, weighted by how far the stream is in a cycle.
void LiveStyle::State::change_at_phase() {
  const int phases = change.phases();
  const double x = phase.phase() * phases;
  const int k0 = std::min(static_cast<int>(x), phases - 1), k1 = (k0 + 1) % phases;
  const double f = x - k0, w = phase.cycle_weight();
  phase_row = k0;
  next_phase_row = k1;
  phase_fraction = f;
  change_local.setZero();
  for (size_t i = 0; i < eased.size(); ++i) {
    if (eased[i] == 0.0) continue;
    const PhaseTable& t = change.cycle[i];
    const double s = eased[i];
    change_local.noalias() += (s * w * (1.0 - f)) * t.row(k0).transpose() + (s * w * f) * t.row(k1).transpose();
    change_local.noalias() += (s * (1.0 - w)) * change.posture[i].transpose();
  }
}

// The changed pose placed with the stream's root and heading, then the stream's bone lengths
// from the hips outward, each bone keeping its direction (limb_length.h). A major joint's bone
// may pass through joints that turn (a neck, a clavicle), so its length is this frame's.
void LiveStyle::State::place_targets() {
  for (Eigen::Index j = 0; j < static_cast<Eigen::Index>(joints.size()); ++j) {
    double dx, dz;
    from_body(heading_cos, heading_sin, local[3 * j] + change_local[3 * j], local[3 * j + 2] + change_local[3 * j + 2], &dx, &dz);
    raw[3 * j] = ground.x() + dx;
    raw[3 * j + 1] = local[3 * j + 1] + change_local[3 * j + 1];
    raw[3 * j + 2] = ground.y() + dz;
  }
  target.segment<3>(0) = raw.segment<3>(0);
  for (size_t j = 1; j < joints.size(); ++j) {
    const int p = parents[j];
    const Eigen::Index c = 3 * static_cast<Eigen::Index>(j);
    const Eigen::Vector3d bone = raw.segment<3>(c) - raw.segment<3>(3 * p);
    const double n = bone.norm();
    // A bone with no direction keeps the stream's own.
    const Eigen::Vector3d direction = n > 0.0 ? Eigen::Vector3d(bone / n)
                                              : Eigen::Vector3d((in.segment<3>(c) - in.segment<3>(3 * p)).normalized());
    target.segment<3>(c) = target.segment<3>(3 * p) + (in.segment<3>(c) - in.segment<3>(3 * p)).norm() * direction;
  }
}

// One style's change of one joint at strength 1 this frame, in the world's axes (Y up): at this
// frame's phase, or (stance) averaged over the stance of foot `side` in the neutral's cycles;
// weighted with the posture change as the stream is in a cycle.
Eigen::Vector3d LiveStyle::State::joint_change(int style, int column, bool stance, int side) const {
  const Eigen::Index c = 3 * column;
  const PhaseTable& t = change.cycle[static_cast<size_t>(style)];
  const Eigen::Vector3d cycle =
      stance ? Eigen::Vector3d(change.planted[static_cast<size_t>(style)][static_cast<size_t>(side)].segment<3>(c).transpose())
             : Eigen::Vector3d(((1.0 - phase_fraction) * t.row(phase_row).segment<3>(c) +
                                phase_fraction * t.row(next_phase_row).segment<3>(c))
                                   .transpose());
  const double w = phase.cycle_weight();
  const Eigen::Vector3d local = w * cycle + (1.0 - w) * change.posture[static_cast<size_t>(style)].segment<3>(c).transpose();
  Eigen::Vector3d world;
  from_body(heading_cos, heading_sin, local.x(), local.z(), &world.x(), &world.z());
  world.y() = local.y();
  return world;
}

// A foot joint's offset from the stream's: while planted, the leg's hold (where the change put
// the foot when it landed, at each style's strength now, so a planted foot stays planted; the toe
// takes the ankle's, so that the planted foot is the stream's moved whole and rolls onto its toe
// as the stream's does), what the landing differed from that settling over
// kLandingSettleSeconds; over a swing, from where the lock held it at the lift to where the next
// stance will hold it (smoothstep over the swing expected), about the change at this phase.
// stance: over a swing, the ankle's change over the neutral's stance at the strengths now.
void LiveStyle::State::lock_joint(LegLock& leg, FootJointLock& joint, int side, bool struck, bool lifted,
                                  const Eigen::Vector3d& stance) {
  if (joint.column < 0) return;
  const Eigen::Vector3d free = at(target, joint.column) - at(in, joint.column);
  Eigen::Vector3d held = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < eased.size(); ++i) held += eased[i] * leg.hold[i];
  if (struck) {  // held from here on
    joint.settle = joint.offset - held;
  } else if (lifted) {  // eased away from here
    joint.lift = joint.offset - free;
  }
  if (leg.planted) {
    joint.offset = (1.0 - smoothstep(double(frames - leg.landed) / std::max(1.0, kLandingSettleSeconds * fps))) * joint.settle;
    joint.offset += held;
    return;
  }
  Eigen::Vector3d toward = stance;
  for (size_t i = 0; i < eased.size(); ++i)
    if (eased[i] != 0.0) toward -= eased[i] * joint_change(static_cast<int>(i), joint.column, false, side);
  const double u = leg.lifted < 0 ? 1.0 : smoothstep(double(frames - leg.lifted) / leg.swing_frames);
  joint.offset = free + (1.0 - u) * joint.lift + u * toward;
}

// Whether the leg is planted this frame (its ankle or its toe is), and whether it struck or lifted
// now. A swing is expected to last as long as the stream's last swing of this foot (from the
// table's stance share of the cycle until the stream has shown one), less the frames it was seen
// late.
void LiveStyle::State::plant_leg(LegLock& leg, int side, bool* struck, bool* lifted) {
  const LiveFoot& ankle = feet.foot(side);
  const LiveFoot& toe = toes.foot(side);
  const bool planted = ankle.planted || toe.planted;
  if (planted && !leg.planted) {
    *struck = true;
    leg.landed = frames;
    for (size_t i = 0; i < eased.size(); ++i) leg.hold[i] = joint_change(static_cast<int>(i), leg.joints[0].column, true, side);
    leg.strike = ankle.planted && toe.planted ? std::min(ankle.strike, toe.strike) : ankle.planted ? ankle.strike : toe.strike;
    if (leg.lift >= 0) leg.last_swing = double(leg.strike - leg.lift);
  } else if (!planted && leg.planted) {
    *lifted = true;
    leg.lifted = frames;
    leg.lift = std::max(ankle.lift, toe.lift);
    const double period = phase.period_frames() > 0 ? phase.period_frames() : change.period_s * fps;
    const double expected = leg.last_swing > 0.0 && leg.last_swing < period
                                ? leg.last_swing
                                : (1.0 - change.stance_share[static_cast<size_t>(side)]) * period;
    leg.swing_frames = std::max(1.0, expected - double(frames - leg.lift));
  }
  leg.planted = planted;
}

// Each leg's ankle and toe at their locked offsets, the knee bent so the leg reaches the ankle
// with its own bones (two-bone IK; a target beyond reach is reached as far as the leg goes, the
// toe moving with the ankle).
void LiveStyle::State::lock_feet() {
  for (int side = 0; side < 2; ++side) {
    LegLock& leg = legs[static_cast<size_t>(side)];
    bool struck = false, lifted = false;
    plant_leg(leg, side, &struck, &lifted);
    Eigen::Vector3d stance = Eigen::Vector3d::Zero();
    if (!leg.planted)
      for (size_t i = 0; i < eased.size(); ++i)
        if (eased[i] != 0.0) stance += eased[i] * joint_change(static_cast<int>(i), leg.joints[0].column, true, side);
    for (FootJointLock& joint : leg.joints) lock_joint(leg, joint, side, struck, lifted, stance);
    const LegColumns& c = rig.legs[static_cast<size_t>(side)];
    Eigen::Vector3d wanted = at(in, c.ankle) + leg.joints[0].offset;
    wanted.y() = std::max(wanted.y(), lowest(leg, leg.joints[0].column, feet.floor(side)));
    Eigen::Vector3d forward;
    from_body(heading_cos, heading_sin, 0.0, 1.0, &forward.x(), &forward.z());
    forward.y() = 0.0;
    // Only where the lock moves the ankle: the solve itself moves a nearly straight knee (its
    // bend is the square root of a difference that vanishes).
    Eigen::Vector3d ankle = at(target, c.ankle);
    if ((wanted - ankle).norm() > kUnchanged * body_height) {
      TwoBoneIkJob ik;
      ik.start = at(target, c.hip);
      ik.mid = at(target, c.knee);
      ik.end = ankle;
      ik.target = wanted;
      ik.pole = ik.mid - ik.start;  // the knee's own bend
      ik.bend_fallback = forward;
      const TwoBoneIkResult locked = ik.Run();
      ankle = locked.end;
      target.segment<3>(3 * c.knee) = locked.mid;
      target.segment<3>(3 * c.ankle) = ankle;
    }
    if (c.toe >= 0 && leg.joints[1].column >= 0) {
      // The toe where its lock puts it, moved with the ankle, on the foot's own length from the
      // ankle (the solve aims the foot at it: a toe target nearer the ankle than the foot is long
      // would tip the toe down), and above its lowest (the foot tipped up to it where needed).
      const Eigen::Vector3d own = at(in, c.toe) - at(in, c.ankle);
      const Eigen::Vector3d aim = at(in, c.toe) + leg.joints[1].offset + (ankle - wanted) - ankle;
      const double length = own.norm();
      Eigen::Vector3d toe = ankle + (aim.norm() > 0.0 ? Eigen::Vector3d(length * aim.normalized()) : own);
      const double low = lowest(leg, leg.joints[1].column, toes.floor(side));
      if (toe.y() < low) {
        const double dy = std::clamp(low - ankle.y(), -length, length);
        Eigen::Vector2d across(toe.x() - ankle.x(), toe.z() - ankle.z());
        if (across.norm() == 0.0) across = Eigen::Vector2d(own.x(), own.z());
        if (across.norm() > 0.0) across.normalize();
        const double reach = std::sqrt(std::max(0.0, length * length - dy * dy));
        toe = ankle + Eigen::Vector3d(reach * across.x(), dy, reach * across.y());
      }
      target.segment<3>(3 * c.toe) = toe;
    }
  }
}

// The lowest a foot joint may go this frame: its planted level (the stream's floor under it, and
// the height its hold adds at the strengths now) plus the stream's own height above that floor,
// up to kSwingClearance.
double LiveStyle::State::lowest(const LegLock& leg, int column, double floor) const {
  double level = floor;
  for (size_t i = 0; i < eased.size(); ++i) level += eased[i] * leg.hold[i].y();
  return level + std::min(in[3 * column + 1] - floor, kSwingClearance * body_height);
}

// Each joint's change moves at most kChangeSpeedShare of the stream's fastest joint step lately
// from the frame before's (the first frame has none before it).
void LiveStyle::State::limit_speed() {
  const double limit = kChangeSpeedShare * fastest;
  for (Eigen::Index j = 0; j < static_cast<Eigen::Index>(joints.size()); ++j) {
    Eigen::Vector3d d = target.segment<3>(3 * j) - in.segment<3>(3 * j);
    if (frames > 0) {
      const Eigen::Vector3d step = d - previous_delta.segment<3>(3 * j);
      const double n = step.norm();
      if (n > limit) d = previous_delta.segment<3>(3 * j) + step * (limit / n);
    }
    delta.segment<3>(3 * j) = d;
  }
}

// The stream skeleton's rotations from the changed positions, in the stream's axes.
void LiveStyle::State::solve(const double* values, double* out) {
  for (Eigen::Index j = 0; j < static_cast<Eigen::Index>(joints.size()); ++j)
    solve_targets.segment<3>(3 * j) = up.transpose() * (in.segment<3>(3 * j) + delta.segment<3>(3 * j));
  if (copied) solver.restart();  // the frame before was not solved: start from the stream's angles
  solver.solve(values, solve_targets.data(), out);
}

LiveStyle::LiveStyle(const Skeleton& skeleton, double fps, const LiveStyleSpec& spec) {
  check_spec(spec, fps);
  check_strengths(spec.strengths, spec.takes.size() - 1);
  // The stream's major joints, and the takes prepared on those of them they share.
  const MajorMapping mapping = map_major_joints(skeleton);
  PrepareOptions options;
  options.fps = fps;
  options.only_majors = shared_major_joints(mapping, "the stream's skeleton", mapping, "the stream's skeleton");
  const std::shared_ptr<const PreparedTakes> prepared = prepare_takes(spec.takes, options);
  const PreparedTakes& p = *prepared;
  std::vector<int> joints;
  for (int major : p.majors) joints.push_back(mapping.joint[static_cast<size_t>(major)]);
  const int m = static_cast<int>(joints.size());
  const std::vector<Eigen::Vector3d> rest = rest_positions(skeleton);
  Eigen::RowVectorXd rest_row(3 * m);
  for (int c = 0; c < m; ++c) rest_row.segment<3>(3 * c) = rest[static_cast<size_t>(joints[static_cast<size_t>(c)])].transpose();
  StyleChange change = style_change(p, rest_row);

  const std::vector<double> lengths = bone_lengths(Eigen::MatrixXd(rest_row), p.parents);
  FootRig rig = make_foot_rig(p.majors, lengths, fps);
  rig.body_height = standing_height(p.majors, lengths);
  LivePhaseOptions phase;
  phase.fps = fps;
  phase.leg_length = rig.leg_length;
  phase.cycle_foot = change.cycle_foot;
  phase.other_strike_phase = change.other_strike_phase;
  phase.guess_period_s = change.period_s;
  state_ = std::make_unique<State>(LiveFeet(rig.leg_length, fps), LivePhase(phase),
                                   ExportFrameSolver(skeleton, joints, "the stream's skeleton"));
  State& s = *state_;
  s.skeleton = skeleton;
  s.fps = fps;
  s.majors = p.majors;
  s.parents = p.parents;
  s.joints = joints;
  s.rig = rig;
  s.body_height = rig.body_height;
  s.change = std::move(change);
  s.chain = chain_joints(skeleton, joints);
  s.posed.rotations.assign(skeleton.joints.size(), Eigen::Matrix3d::Identity());
  s.posed.positions.assign(skeleton.joints.size(), Eigen::Vector3d::Zero());
  s.to = spec.strengths;
  s.fastest_decay = std::pow(0.5, 1.0 / (kFastestHalfLifeSeconds * fps));
  s.start_stream();
}

LiveStyle::~LiveStyle() = default;

void LiveStyle::restart() { state_->start_stream(); }

void LiveStyle::set_strengths(const std::vector<double>& strengths) {
  State& s = *state_;
  check_strengths(strengths, s.eased.size());
  s.from = s.eased;
  s.to = strengths;
  s.ease = 0.0;
}

void LiveStyle::style_frame(const double* in, double* out) {
  State& s = *state_;
  // A frame that is not all numbers changes nothing: the frame before is shown again (the
  // stream itself where there is none).
  for (int i = 0; i < s.skeleton.channel_count; ++i)
    if (!std::isfinite(in[i])) {
      std::copy(s.last_out.begin(), s.last_out.end(), out);
      if (s.frames == 0) std::copy(in, in + s.skeleton.channel_count, out);
      return;
    }
  s.pose(in);
  s.to_canonical();
  s.track_gait();
  s.ease_strengths();
  s.change_at_phase();
  s.place_targets();
  s.lock_feet();
  s.limit_speed();
  bool own = s.delta.cwiseAbs().maxCoeff() <= kUnchanged * s.body_height;
  for (double strength : s.eased) own &= strength == 0.0;
  if (own) {  // the stream's own frame, exactly
    std::copy(in, in + s.skeleton.channel_count, out);
    s.delta.setZero();
  } else {
    s.solve(in, out);
  }
  s.copied = own;
  s.previous_delta = s.delta;
  std::copy(out, out + s.skeleton.channel_count, s.last_out.begin());
  ++s.frames;
}

double LiveStyle::phase() const { return state_->phase.phase(); }
bool LiveStyle::in_cycle() const { return state_->phase.in_cycle(); }
double LiveStyle::cycle_weight() const { return state_->phase.cycle_weight(); }
bool LiveStyle::planted(int side) const { return state_->legs.at(static_cast<size_t>(side)).planted; }
const std::vector<double>& LiveStyle::strengths() const { return state_->eased; }
long LiveStyle::frames() const { return state_->frames; }
double LiveStyle::body_height() const { return state_->body_height; }
const std::vector<int>& LiveStyle::major_joints() const { return state_->joints; }

}  // namespace mostyle
