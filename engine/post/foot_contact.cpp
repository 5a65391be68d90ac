#include "engine/post/foot_contact.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "engine/io/error.h"
#include "engine/kinematics/ease.h"
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

Eigen::Vector3d joint_at(const Eigen::MatrixXd& m, Eigen::Index row, int column) {
  return Eigen::Vector3d(m(row, 3 * column), m(row, 3 * column + 1), m(row, 3 * column + 2));
}

void set_joint(Eigen::MatrixXd& m, Eigen::Index row, int column, const Eigen::Vector3d& v) {
  m(row, 3 * column) = v.x();
  m(row, 3 * column + 1) = v.y();
  m(row, 3 * column + 2) = v.z();
}

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
  auto floor_at = [&](Eigen::Index t) {
    const Eigen::Index from = std::clamp<Eigen::Index>(t - half, 0, frames - width);
    std::copy(heights.begin() + from, heights.begin() + from + width, window.begin());
    std::nth_element(window.begin(), window.begin() + static_cast<std::ptrdiff_t>(k), window.end());
    return window[k];
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

void blend_contacts(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double alpha, Eigen::MatrixXd& out) {
  if (a.rows() != b.rows() || a.cols() != 2 || b.cols() != 2)
    throw InputError("foot contacts: expected two F x 2 contact matrices, found " + std::to_string(a.rows()) +
                     " x " + std::to_string(a.cols()) + " and " + std::to_string(b.rows()) + " x " +
                     std::to_string(b.cols()));
  out.resize(a.rows(), 2);
  for (Eigen::Index t = 0; t < a.rows(); ++t)
    for (int s = 0; s < 2; ++s) out(t, s) = (1.0 - alpha) * a(t, s) + alpha * b(t, s) > 0.5 ? 1.0 : 0.0;
}

double foot_sliding(const Eigen::MatrixXd& world, const Eigen::MatrixXd& contacts, const FootRig& rig) {
  check_columns(world, rig, "foot sliding");
  check_contacts(world, contacts, "foot sliding");
  double sum = 0.0;
  long steps = 0;
  for (int side = 0; side < 2; ++side) {
    const int ankle = rig.legs[side].ankle;
    if (ankle < 0) continue;
    for (Eigen::Index t = 0; t + 1 < world.rows(); ++t) {
      if (contacts(t, side) <= 0.5 || contacts(t + 1, side) <= 0.5) continue;
      const double dx = world(t + 1, 3 * ankle) - world(t, 3 * ankle);
      const double dz = world(t + 1, 3 * ankle + 2) - world(t, 3 * ankle + 2);
      sum += std::sqrt(dx * dx + dz * dz) * rig.fps;
      ++steps;
    }
  }
  return steps > 0 ? sum / static_cast<double>(steps) : 0.0;
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
