#include "engine/measure/foot_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/base/error.h"
#include "engine/kinematics/joint_rows.h"
#include "engine/measure/planted_feet.h"
#include "engine/prepare/major_skeleton.h"
#include "engine/prepare/major_take.h"

namespace mostyle {
namespace {

constexpr double kFloorPercentile = 0.05;  // of the ankle's heights: its height when planted
constexpr double kTimeEpsilon = 1e-9;
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

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
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

int FootRig::max_gap_frames() const {
  return static_cast<int>(std::floor(options.max_gap_seconds * fps + kTimeEpsilon));
}

void FootRig::check_columns(const Eigen::MatrixXd& world, const char* where) const {
  for (const LegColumns& leg : legs) {
    for (int c : {leg.hip, leg.knee, leg.ankle, leg.toe}) {
      if (c >= 0 && 3 * static_cast<Eigen::Index>(c) + 2 >= world.cols())
        throw InputError(std::string(where) + ": positions have " + std::to_string(world.cols()) +
                         " columns, too few for joint column " + std::to_string(c));
    }
  }
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
  rig.check_columns(world, "foot contacts");
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
  const int max_gap = rig.max_gap_frames();
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

}  // namespace mostyle
