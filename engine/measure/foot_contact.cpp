#include "engine/measure/foot_contact.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/base/error.h"
#include "engine/kinematics/ease.h"
#include "engine/kinematics/joint_rows.h"
#include "engine/measure/planted_feet.h"
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
// Bisection steps for a run's fitting shift (fitting_shift): 2^-30 of the balanced shift.
constexpr int kFitShiftSteps = 30;
// How far (leg lengths) the knee's pole leans towards where the foot points (apply_foot_lock).
constexpr double kKneeForwardBias = 0.02;
// The toe bias is whole once the lock moves the ankle this many leg lengths, less below.
constexpr double kKneeBiasMove = 0.05;
// The lock keeps the ankle within this fraction of the leg's full length from the hip.
constexpr double kReachMargin = 0.995;
constexpr double kPi = 3.14159265358979323846;
// The floor under a foot is its low percentile within this many seconds either side of a frame,
// taken every kFloorHopSeconds.
constexpr double kFloorWindowSeconds = 0.75;
constexpr double kFloorHopSeconds = 0.1;
// Hips whose ground point moves on slower than this (leg lengths per second, over
// kTravelWindowSeconds) stay in place: the take's planted feet slide backwards under the body.
constexpr double kInPlaceTravel = 0.2;
constexpr double kTravelWindowSeconds = 1.0;
// A foot landing in the take's last frames may still be this many times faster than a planted one.
constexpr double kLandingSpeed = 3.0;
// An in-place take's planted foot moves with the belt within this share of the belt's speed.
constexpr double kBeltTolerance = 0.5;
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

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
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

// Any unit vector perpendicular to n (unit).
Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d axis = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(axis).normalized();
}

// The pelvis's ground point (x, z: the middle of the usable hip joints) and the body's heading
// (the angle of the hip axis on the ground, radians, unwrapped; 0 without both hips) per frame.
struct BodyPath {
  Eigen::MatrixXd ground;   // F x 2
  Eigen::VectorXd heading;  // F
};

BodyPath body_path(const Eigen::MatrixXd& world, const FootRig& rig) {
  const Eigen::Index frames = world.rows();
  BodyPath path{Eigen::MatrixXd::Zero(frames, 2), Eigen::VectorXd::Zero(frames)};
  const int left = rig.legs[0].hip, right = rig.legs[1].hip;
  for (Eigen::Index t = 0; t < frames; ++t) {
    int n = 0;
    for (int hip : {left, right}) {
      if (hip < 0) continue;
      path.ground(t, 0) += world(t, 3 * hip);
      path.ground(t, 1) += world(t, 3 * hip + 2);
      ++n;
    }
    if (n > 0) path.ground.row(t) /= n;
    if (left < 0 || right < 0) continue;
    const double dx = world(t, 3 * right) - world(t, 3 * left), dz = world(t, 3 * right + 2) - world(t, 3 * left + 2);
    double angle = dx == 0.0 && dz == 0.0 ? (t > 0 ? path.heading[t - 1] : 0.0) : std::atan2(dz, dx);
    if (t > 0) angle += 2.0 * kPi * std::round((path.heading[t - 1] - angle) / (2.0 * kPi));
    path.heading[t] = angle;
  }
  return path;
}

// The mean of v over the frames within `half` frames of each (fewer at the ends). O(F).
Eigen::VectorXd moving_average(const Eigen::VectorXd& v, double half) {
  const Eigen::Index n = v.size(), h = std::max<Eigen::Index>(0, static_cast<Eigen::Index>(std::lround(half)));
  Eigen::VectorXd sums(n + 1);
  sums[0] = 0.0;
  for (Eigen::Index t = 0; t < n; ++t) sums[t + 1] = sums[t] + v[t];
  Eigen::VectorXd out(n);
  for (Eigen::Index t = 0; t < n; ++t) {
    const Eigen::Index a = std::max<Eigen::Index>(0, t - h), b = std::min(n, t + h + 1);
    out[t] = (sums[b] - sums[a]) / double(b - a);
  }
  return out;
}

// Whether the hips stay in place: their ground point moves on slower than kInPlaceTravel leg
// lengths per second, on average, measured over kTravelWindowSeconds (sway to and fro cancels).
bool stays_in_place(const BodyPath& path, const FootRig& rig) {
  const Eigen::Index frames = path.ground.rows();
  if (frames < 2 || !(rig.leg_length > 0)) return false;
  const Eigen::Index w =
      std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::lround(kTravelWindowSeconds * rig.fps)), 1, frames - 1);
  double sum = 0.0;
  for (Eigen::Index t = 0; t + w < frames; ++t) sum += (path.ground.row(t + w) - path.ground.row(t)).norm();
  const double speed = sum / double(frames - w) * rig.fps / double(w);
  return speed < kInPlaceTravel * rig.leg_length;
}

// The floor under one foot at each frame: a low percentile of its ankle's height within
// kFloorWindowSeconds (a window of that size or the whole take when shorter, moved inside the
// take at its ends), so a ground that rises or falls over a take is followed; taken every
// kFloorHopSeconds and linear in between. heights: F. O(F x window / hop).
std::vector<double> floor_levels(const std::vector<double>& heights, double fps) {
  const Eigen::Index frames = static_cast<Eigen::Index>(heights.size());
  const Eigen::Index half = std::max<Eigen::Index>(1, static_cast<Eigen::Index>(std::lround(kFloorWindowSeconds * fps)));
  const Eigen::Index hop = std::max<Eigen::Index>(1, static_cast<Eigen::Index>(std::lround(kFloorHopSeconds * fps)));
  const Eigen::Index width = std::min(frames, 2 * half + 1);
  const size_t k = static_cast<size_t>(kFloorPercentile * static_cast<double>(width - 1));
  std::vector<double> window(static_cast<size_t>(width));
  // Only the heights up to a bound take part in the selection when at least k + 1 of the window's
  // are under it: its (k+1)-th lowest is then among them, the same value. The bound is the last
  // window's floor raised by how far its lowest height was below it, so that a floor moving
  // slowly keeps the heights selected from to a few dozen; else the whole window.
  double bound = std::numeric_limits<double>::infinity();
  auto floor_at = [&](Eigen::Index t) {
    const Eigen::Index from = std::clamp<Eigen::Index>(t - half, 0, frames - width);
    size_t kept = 0;
    for (Eigen::Index u = from; u < from + width; ++u) {
      const double h = heights[static_cast<size_t>(u)];
      window[kept] = h;
      kept += h <= bound ? 1 : 0;
    }
    if (kept <= k) {
      std::copy(heights.begin() + from, heights.begin() + from + width, window.begin());
      kept = static_cast<size_t>(width);
    }
    const auto begin = window.begin(), end = window.begin() + static_cast<std::ptrdiff_t>(kept);
    std::nth_element(begin, begin + static_cast<std::ptrdiff_t>(k), end);
    const double floor = window[k], lowest = *std::min_element(begin, begin + static_cast<std::ptrdiff_t>(k) + 1);
    bound = floor + 2.0 * (floor - lowest);
    return floor;
  };
  std::vector<double> out(heights.size());
  double previous = floor_at(0);
  for (Eigen::Index t = 0; t < frames; t += hop) {
    const Eigen::Index next = std::min(frames - 1, t + hop);
    const double at_next = next > t ? floor_at(next) : previous;
    for (Eigen::Index u = t; u <= next; ++u)
      out[static_cast<size_t>(u)] = previous + (at_next - previous) * double(u - t) / double(std::max<Eigen::Index>(1, next - t));
    previous = at_next;
  }
  return out;
}

// Contacts of a take (not a loop): see detect_foot_contacts.
Eigen::MatrixXd contacts_of(const Eigen::MatrixXd& world, const FootRig& rig) {
  const Eigen::Index frames = world.rows();
  Eigen::MatrixXd contacts = Eigen::MatrixXd::Zero(frames, 2);
  if (frames == 0) return contacts;
  const FootContactOptions& o = rig.options;
  const double max_height = o.height_fraction * rig.leg_length;
  const double max_speed = o.speed_fraction * rig.leg_length;
  const BodyPath path = body_path(world, rig);
  const bool in_place = stays_in_place(path, rig);
  // The body's frame for an in-place take's ankle velocities: its heading averaged over
  // kTravelWindowSeconds, so that hips twisting to and fro within a stride (a run's) do not swing
  // the belt around.
  const Eigen::VectorXd heading =
      in_place ? moving_average(path.heading, kTravelWindowSeconds * rig.fps / 2.0) : Eigen::VectorXd();
  std::vector<double> heights(static_cast<size_t>(frames));
  std::vector<char> low(static_cast<size_t>(frames));
  // The ankle's velocity; in place, x and z in the body's frame (along the hip axis, across it).
  Eigen::MatrixXd velocity(frames, 3);
  for (int side = 0; side < 2; ++side) {
    const LegColumns& leg = rig.legs[side];
    if (!leg.usable()) continue;
    for (Eigen::Index t = 0; t < frames; ++t) heights[t] = world(t, 3 * leg.ankle + 1);
    // The floor under this foot: a low percentile of the ankle's own height near each frame, so
    // a take whose ground is not at 0 (or a skeleton whose ankle is high above its sole) needs no
    // setting.
    const std::vector<double> floor = floor_levels(heights, rig.fps);
    for (Eigen::Index t = 0; t < frames; ++t) {
      low[t] = heights[t] - floor[t] <= max_height;
      // Central differences (one-sided at the ends): the velocity at the frame itself.
      const Eigen::Index t0 = std::max<Eigen::Index>(0, t - 1), t1 = std::min(frames - 1, t + 1);
      const Eigen::Vector3d v = t1 > t0 ? Eigen::Vector3d((joint_at(world, t1, leg.ankle) - joint_at(world, t0, leg.ankle)) *
                                                          rig.fps / double(t1 - t0))
                                        : Eigen::Vector3d::Zero();
      if (!in_place) {  // a take that travels: the velocity as it is (only its size is read)
        velocity.row(t) = v.transpose();
        continue;
      }
      const double c = std::cos(heading[t]), s = std::sin(heading[t]);
      velocity.row(t) << c * v.x() + s * v.z(), v.y(), -s * v.x() + c * v.z();
    }
    // A take whose hips stay in place (a game's walk or run loop, a treadmill) moves its planted
    // foot backwards under the body at the walking speed: speeds are measured against that
    // "belt", the median velocity of the ankle while it is low, and allowed kBeltTolerance of it.
    // A take that travels plants its feet still: the belt is zero.
    Eigen::Vector2d belt = Eigen::Vector2d::Zero();
    if (in_place) {
      std::vector<double> bx, bz;
      for (Eigen::Index t = 0; t < frames; ++t)
        if (low[t]) {
          bx.push_back(velocity(t, 0));
          bz.push_back(velocity(t, 2));
        }
      belt = Eigen::Vector2d(median_of(bx), median_of(bz));
    }
    const double allowed = std::max(max_speed, kBeltTolerance * belt.norm());
    std::vector<double> speed(static_cast<size_t>(frames));
    for (Eigen::Index t = 0; t < frames; ++t) {
      const double dx = velocity(t, 0) - belt.x(), dz = velocity(t, 2) - belt.y();
      speed[t] = std::sqrt(dx * dx + velocity(t, 1) * velocity(t, 1) + dz * dz);
      contacts(t, side) = low[t] && speed[t] <= allowed ? 1.0 : 0.0;
    }
    // A landing that the take's end cuts short: the foot is still slowing down on the floor. One
    // that came down from a swing (no contact since) and stays low and slower than
    // kLandingSpeed times the planted speed to the last frame is in contact from there.
    Eigen::Index from = frames;
    while (from > 0 && low[from - 1] && speed[from - 1] <= kLandingSpeed * allowed && contacts(from - 1, side) == 0.0)
      --from;
    if (from < frames && from > 0 && contacts(from - 1, side) == 0.0) contacts.col(side).tail(frames - from).setOnes();
  }
  tidy_contacts(contacts, rig);
  return contacts;
}

// Three repeats of a loop of L frames (3L x 3M): the loop's frames [0, L) moved back by one
// repeat, as they are, and moved on by one. A repeat moves the body by the loop's travel and turn:
// frame L's pelvis and heading against frame 0's (frame L is the last frame when it repeats the
// first, else one step on from the last: the mean of the first and last frames' steps).
Eigen::MatrixXd tile_loop(const Eigen::MatrixXd& world, const FootRig& rig, Eigen::Index L) {
  const Eigen::Index frames = world.rows();
  const BodyPath path = body_path(world, rig);
  Eigen::Vector2d end_ground = path.ground.row(std::min(L, frames - 1)).transpose();
  double end_heading = path.heading[std::min(L, frames - 1)];
  if (L == frames && frames >= 2) {
    end_ground += 0.5 * (path.ground.row(frames - 1) - path.ground.row(frames - 2) + path.ground.row(1) -
                         path.ground.row(0)).transpose();
    end_heading += 0.5 * (path.heading[frames - 1] - path.heading[frames - 2] + path.heading[1] - path.heading[0]);
  }
  const double turn = end_heading - path.heading[0];
  const Eigen::Vector2d start_ground = path.ground.row(0).transpose();
  // p -> R(sign * turn) (p - from) + to on the ground plane, y kept. R turns the hip axis as the
  // heading (atan2(z, x)) grows.
  auto moved = [&](Eigen::Index f, double sign, const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
    const double c = std::cos(sign * turn), s = std::sin(sign * turn);
    Eigen::RowVectorXd row = world.row(f);
    for (Eigen::Index j = 0; 3 * j + 2 < row.size(); ++j) {
      const double x = row[3 * j] - from.x(), z = row[3 * j + 2] - from.y();
      row[3 * j] = c * x - s * z + to.x();
      row[3 * j + 2] = s * x + c * z + to.y();
    }
    return row;
  };
  // Back by one repeat: frame L's place goes to frame 0's, turned back.
  Eigen::MatrixXd tiled(3 * L, world.cols());
  for (Eigen::Index f = 0; f < L; ++f) {
    tiled.row(f) = moved(f, -1.0, end_ground, start_ground);
    tiled.row(L + f) = world.row(f);
    tiled.row(2 * L + f) = moved(f, 1.0, start_ground, end_ground);
  }
  return tiled;
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

Eigen::MatrixXd detect_foot_contacts(const Eigen::MatrixXd& world, const FootRig& rig, int loop_frames) {
  check_columns(world, rig, "foot contacts");
  const Eigen::Index frames = world.rows();
  if (loop_frames == 0 || frames == 0) return contacts_of(world, rig);
  if (loop_frames < 2 || loop_frames > frames)
    throw InputError("foot contacts: a loop of " + std::to_string(loop_frames) + " frames does not fit the take's " +
                     std::to_string(frames));
  // Three repeats of the loop, each moved on by the loop's travel and turn: the middle one's
  // contacts are those of a loop played on repeat (a contact that runs across its end is whole).
  const Eigen::Index L = loop_frames;
  const Eigen::MatrixXd tiled = tile_loop(world, rig, L);
  const Eigen::MatrixXd all = contacts_of(tiled, rig);
  Eigen::MatrixXd contacts(frames, 2);
  for (Eigen::Index f = 0; f < frames; ++f) contacts.row(f) = all.row(L + f % L);
  return contacts;
}

void tidy_contacts(Eigen::MatrixXd& contacts, const FootRig& rig) {
  const FootContactOptions& o = rig.options;
  const int max_gap = seconds_to_frames(o.max_gap_seconds, rig.fps);
  // To the nearest frame: 0.1 s is 2.4 frames at 24 fps, and a run's short stance there is 2.
  const int min_run = std::max(1, static_cast<int>(std::lround(o.min_contact_seconds * rig.fps - kTimeEpsilon)));
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
      // A contact cut by the take's first or last frame may have lasted longer: it stays (the
      // last frames' landing is a foot strike).
      if (e - t < min_run && t > 0 && e < frames) planted.segment(t, e - t).setZero();
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

std::vector<int> foot_strikes(const Eigen::MatrixXd& contacts, int foot) {
  std::vector<int> out;
  for (Eigen::Index t = 1; t < contacts.rows(); ++t)
    if (contacts(t, foot) > 0.5 && contacts(t - 1, foot) <= 0.5) out.push_back(static_cast<int>(t));
  return out;
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

namespace {

// One leg as the lock's steps see it: its columns, and its ankle's and toe's foot joints
// (planted_feet.h order; a toe column of -1 where the rig has none).
struct LockedLeg {
  LegColumns columns;
  int joints[2];
};

// The runs of frames the leg's foot is pinned over (scratch.pinned, scratch.runs): every frame one
// of its joints is planted (planted_feet.h, the measure the output is judged by), breaks of up to
// max_gap filled. Short runs are kept: a planted step left out would slide. O(F).
void find_runs(const LockedLeg& leg, int max_gap, FootLockScratch& s) {
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
  s.runs.clear();
  for (Eigen::Index t = 0; t < frames;) {
    if (!s.pinned[t]) {
      ++t;
      continue;
    }
    Eigen::Index end = t;
    while (end + 1 < frames && s.pinned[end + 1]) ++end;
    s.runs.emplace_back(t, end);
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

// Within each run, the turn about the vertical (s.yaw) that holds the foot's heading where both
// its joints are planted, as run_offsets holds its place: each step's turn beyond what the drift
// allows (share of it; never more than the step turned) taken out, centred on the run, and faded
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
  for (const auto& [start, end] : s.runs) {
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
    auto run = s.yaw.segment(start, end - start + 1);
    run.array() -= run.mean();
  }
  for (size_t r = 0; r < s.runs.size(); ++r) {
    const auto [start, end] = s.runs[r];
    const Eigen::Index before = r > 0 ? s.runs[r - 1].second + 1 : 0;
    const Eigen::Index after = r + 1 < s.runs.size() ? s.runs[r + 1].first - 1 : frames - 1;
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

// Within each run, the offset (s.target) that takes out, step by step, what the foot's planted
// joints move beyond what they may (share of drift; none: nothing), so they move by that much and never
// faster than they did; centred on the run (the least total correction). A step's move is its
// planted joints' averaged, each weighted by how near it is to its floor (a heel lifting off
// leaves the toe to hold the foot; a toe coming down, the heel); a step with neither joint
// planted at both ends (a filled break) keeps the offset. O(F).
void run_offsets(const Eigen::MatrixXd& world, const LockedLeg& leg, const std::array<int, kFootJoints>& columns,
                 const std::array<double, kFootJoints>& floors, double band, const Eigen::MatrixXd* drift,
                 double share, FootLockScratch& s) {
  for (const auto& [start, end] : s.runs) {
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

// How far the offset has gone from one run's to the next's at each frame of the swings between
// runs (s.swing: 0 at a run's last frame, 1 at the next's first). Each step takes a share of the
// change that grows with the room the foot has under `fastest` (units a frame) on that step, its
// ankle's or toe's own speed taken off, times a bump that starts and ends at zero (no jump in
// speed at lift-off or landing): the change goes where the swinging foot is slow, not where it is
// fastest. A plain smoothstep put most of it mid-swing, where a foot is at its fastest, and left
// the lock no room to pin a stride the takes' feet do not take (a style's shorter steps under the
// content's pace). Without a limit (fastest 0), the bump alone. O(F).
void swing_profile(const Eigen::MatrixXd& world, const LockedLeg& leg, double fastest, FootLockScratch& s) {
  const Eigen::Index frames = world.rows();
  s.swing.setZero(frames);
  for (size_t r = 1; r < s.runs.size(); ++r) {
    const Eigen::Index from = s.runs[r - 1].second, to = s.runs[r].first, span = to - from;
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
    if (!(total > 0.0)) {  // no step with room: the bump alone (the run is then not pinned)
      total = 0.0;
      for (Eigen::Index u = from; u < to; ++u) s.swing[u + 1] = total += bump(u);
    }
    for (Eigen::Index u = from + 1; u <= to; ++u) s.swing[u] /= total;
  }
}

// The shift (taken off every offset of a run) that lets a run's offsets at its ends (first,
// last) fit the rooms before and after it, or come as near as they can: the offsets are centred
// on the run (the least total correction), so where one side's swing has little room and the
// other's much, the whole pin would be scaled down to the smaller room although moving the pinned
// spot towards the roomier side fits it. The shift goes from none towards the balanced one (the
// two ends' offsets in proportion to their rooms, the largest fit), only as far as the fit needs
// (bisection on that way; each end's distance is convex along it, so where the balanced shift
// fits, the shifts that fit from there back towards none are one stretch). A run that fits as it
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

// Each run's offsets, shifted as fitting_shift finds, then scaled down where the change of offset before or after it (spread over a
// swing as s.swing shares it, or a fade) would move the foot faster than `fastest` units a frame: on every step of the
// swing the foot's own speed plus the offset's change at most that (each run may take half of a
// swing's room, a fade's whole). A run next to a swing of a few frames (a foot that barely leaves
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
  for (size_t r = 0; r < s.runs.size(); ++r) {
    // Plain variables, not a structured binding: C++17 lambdas cannot capture those.
    const Eigen::Index start = s.runs[r].first, end = s.runs[r].second;
    double before, after;
    if (r == 0) {
      before = room(start - ramp - 1, start, [&](Eigen::Index u) {
        return u >= start ? 1.0 : u < start - ramp ? 0.0 : smoothstep(1.0 - double(start - u) / (ramp + 1));
      });
    } else {
      const Eigen::Index from = s.runs[r - 1].second;
      before = 0.5 * room(from, start, [&](Eigen::Index u) { return u <= from ? 0.0 : s.swing[u]; });
    }
    if (r + 1 == s.runs.size()) {
      after = room(end, end + ramp + 1, [&](Eigen::Index u) {
        return u <= end ? 1.0 : u > end + ramp ? 0.0 : smoothstep(1.0 - double(u - end) / (ramp + 1));
      });
    } else {
      const Eigen::Index to = s.runs[r + 1].first;
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

// The offsets between runs (s.target, s.weight 1 wherever the ankle moves, s.ease): the change
// from one run to the next spread over the whole swing as swing_profile shares it (s.swing: no
// jump in speed at landing or lift-off, most of it on the swing's slow steps); before the first
// run and after the last a fade over ramp frames. O(F).
void ease_between_runs(Eigen::Index frames, int ramp, FootLockScratch& s) {
  s.weight.setZero(frames);
  s.ease.setConstant(frames, -1.0);
  for (size_t r = 0; r < s.runs.size(); ++r) {
    const auto [start, end] = s.runs[r];
    s.weight.segment(start, end - start + 1).setOnes();
    if (r > 0) {  // the swing from the previous run
      const Eigen::Index previous_end = s.runs[r - 1].second;
      for (Eigen::Index u = previous_end + 1; u < start; ++u) {
        const double f = s.swing[u];
        s.weight[u] = 1.0;
        s.ease[u] = f;
        s.target.row(u) = (1.0 - f) * s.target.row(previous_end) + f * s.target.row(start);
      }
    } else {  // fade in before the first run
      for (Eigen::Index u = std::max<Eigen::Index>(0, start - ramp); u < start; ++u) {
        const double f = smoothstep(1.0 - static_cast<double>(start - u) / (ramp + 1));
        s.weight[u] = 1.0;
        s.target.row(u) = f * s.target.row(start);
      }
    }
    if (r + 1 == s.runs.size())  // fade out after the last run
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
  if (rig_legs[0].hip >= 0 && rig_legs[1].hip >= 0) {
    const Eigen::Vector3d across = joint_at(world, t, rig_legs[0].hip) - joint_at(world, t, rig_legs[1].hip);
    Eigen::Vector3d facing(-across.z(), 0.0, across.x());  // across x up, horizontal
    if (facing.norm() > 0) {
      facing.normalize();
      const double back = pole.dot(facing);
      if (back < 0.0) pole -= moving * back * facing;
    }
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
// in a jump), and what follows a run eases from where the foot was, not from where the leg could
// not reach. O(F).
// rig_legs: the legs' columns in world (their hips read for the way the body faces).
template <typename Matrix>
void move_leg(Matrix& world, const LegColumns& leg, const std::array<LegColumns, 2>& rig_legs, const FootRig& rig,
              FootLockScratch& s) {
  const Eigen::Index frames = world.rows();
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
  // The offset applied on the frame before (0 where the lock left the leg alone), the target
  // then, and how much the offset fell short of the target on the last frame of the last run.
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
    Eigen::Vector3d new_knee, new_ankle;
    two_bone_ik_pole(hip, knee, ankle, target, straight ? before : pole, before, &new_knee, &new_ankle);
    set_joint(world, t, leg.knee, new_knee);
    set_joint(world, t, leg.ankle, new_ankle);
    if (leg.toe >= 0) set_joint(world, t, leg.toe, joint_at(world, t, leg.toe) + (new_ankle - ankle));
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
  for (int side = 0; side < 2; ++side) {
    const LockedLeg leg{rig.legs[static_cast<size_t>(side)], {2 * side, 2 * side + 1}};
    if (!leg.columns.usable()) continue;
    for (int b = 0; b < 3; ++b) {
      const int c = b == 0 ? leg.columns.knee : b == 1 ? leg.columns.ankle : leg.columns.toe;
      if (c >= 0) scratch.before.middleCols(3 * b, 3) = world.middleCols(3 * c, 3);
    }
    find_runs(leg, seconds_to_frames(rig.options.max_gap_seconds, rig.fps), scratch);
    scratch.target.setZero();
    hold_foot_heading(world, leg, drift, share, ramp, scratch);
    run_offsets(world, leg, columns, floors, kPlantedHeightFraction * rig.body_height, drift, share, scratch);
    swing_profile(world, leg, max_speed / rig.fps, scratch);
    if (max_speed > 0.0) fit_to_swings(world, leg, ramp, max_speed / rig.fps, scratch);
    ease_between_runs(frames, ramp, scratch);
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
  check_columns(world, rig, "foot lock");
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
  // Allowing all the drift, the planted feet may still move faster than planted_speed (the
  // output's planted steps fall where the takes' move most); then less of it is allowed: none,
  // and if that is under the limit, the largest share found (regula falsi, Illinois' variant: the
  // measure need not be straight in the share, a few tries) that keeps the measure under it: the
  // least pinning that holds the limit. The heights stay, so one planted mask serves every try.
  const double limit = limits.planted_speed;
  copy_leg_columns(world, rig, scratch.original, false);
  lock_legs(world, rig, floors, drift, 1.0, limits.fastest_joint, scratch);
  double high = 1.0, at_high = planted_speed(world, scratch.planted, rig).speed;
  if (at_high <= limit) return;
  copy_leg_columns(world, rig, scratch.original, true);
  lock_legs(world, rig, floors, drift, 0.0, limits.fastest_joint, scratch);
  double low = 0.0, at_low = planted_speed(world, scratch.planted, rig).speed;
  if (at_low >= limit) return;
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
}

}  // namespace mostyle
