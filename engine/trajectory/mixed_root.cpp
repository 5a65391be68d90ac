#include "engine/trajectory/mixed_root.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace mostyle {

void integrate_root_towards(const Eigen::MatrixXd& steps, const Eigen::MatrixXd& target, double start_heading,
                            double fps, double pull_seconds, Eigen::MatrixXd* ground, Eigen::VectorXd* heading) {
  assert(steps.cols() == 3 && target.rows() == steps.rows() && target.cols() == 2);
  const Eigen::Index frames = steps.rows();
  ground->resize(frames, 2);
  heading->resize(frames);
  if (frames == 0) return;
  const double pull = pull_seconds > 0 && fps > 0 ? 1.0 - std::exp(-1.0 / (fps * pull_seconds)) : 0.0;
  (*ground)(0, 0) = target(0, 0);
  (*ground)(0, 1) = target(0, 1);
  (*heading)[0] = start_heading;
  for (Eigen::Index t = 0; t + 1 < frames; ++t) {
    const double c = std::cos((*heading)[t]), s = std::sin((*heading)[t]);
    // integrate_root's step, then a first-order pull towards the target path.
    const double x = (*ground)(t, 0) + c * steps(t, 0) + s * steps(t, 1);
    const double z = (*ground)(t, 1) - s * steps(t, 0) + c * steps(t, 1);
    (*ground)(t + 1, 0) = x + pull * (target(t + 1, 0) - x);
    (*ground)(t + 1, 1) = z + pull * (target(t + 1, 1) - z);
    (*heading)[t + 1] = (*heading)[t] + steps(t, 2);
  }
}

namespace {

// The gap d >= 0 on a leash: itself within leash / 2, beyond eased towards the leash.
double leashed(double d, double leash) {
  const double free = 0.5 * leash, ease = leash - free;
  return d <= free ? d : free + ease * std::tanh((d - free) / ease);
}

}  // namespace

void keep_near_path(Eigen::MatrixXd& ground, const Eigen::Ref<const Eigen::MatrixXd>& path, double leash) {
  assert(path.rows() == ground.rows() && path.cols() == 2 && ground.cols() == 2);
  if (!(leash > 0.0)) return;
  for (Eigen::Index t = 0; t < ground.rows(); ++t) {
    const double dx = ground(t, 0) - path(t, 0), dz = ground(t, 1) - path(t, 1);
    const double gap = std::hypot(dx, dz);
    if (gap <= 0.5 * leash) continue;
    const double scale = leashed(gap, leash) / gap;
    ground(t, 0) = path(t, 0) + scale * dx;
    ground(t, 1) = path(t, 1) + scale * dz;
  }
}

void remove_path_drift(Eigen::MatrixXd& ground, const Eigen::Ref<const Eigen::MatrixXd>& path, Eigen::Index window,
                       Eigen::MatrixXd& scratch) {
  assert(path.rows() == ground.rows() && path.cols() == 2 && ground.cols() == 2);
  const Eigen::Index n = ground.rows();
  if (window <= 1 || n < 2) return;
  // scratch row t + 1: the sum of the gaps of samples 0..t (row 0: zero).
  scratch.resize(n + 1, 2);
  scratch.row(0).setZero();
  for (Eigen::Index t = 0; t < n; ++t) scratch.row(t + 1) = scratch.row(t) + (ground.row(t) - path.row(t));
  const Eigen::Index half = window / 2;
  // Each mean from the sums before any gap is changed: ground is written row by row below.
  Eigen::Vector2d mean;
  for (Eigen::Index t = 0; t < n; ++t) {
    const Eigen::Index a = std::max<Eigen::Index>(0, t - half), b = std::min<Eigen::Index>(n, t + half + 1);
    mean = (scratch.row(b) - scratch.row(a)).transpose() / static_cast<double>(b - a);
    ground.row(t) -= mean.transpose();
  }
}

void keep_near_heading(Eigen::VectorXd& heading, const Eigen::Ref<const Eigen::VectorXd>& path, double leash) {
  assert(path.size() == heading.size());
  if (!(leash > 0.0)) return;
  for (Eigen::Index t = 0; t < heading.size(); ++t) {
    const double gap = std::remainder(heading[t] - path[t], 2.0 * 3.14159265358979323846);
    const double size = std::abs(gap);
    if (size > 0.5 * leash) heading[t] -= std::copysign(size - leashed(size, leash), gap);
  }
}

namespace {

// The root's travel over samples a..b (ground U x 2) in the body frame at sample t (heading[t]):
// R_y(-heading) of the world move (canonical_frame.h), per second.
Eigen::Vector2d body_travel(const Eigen::MatrixXd& ground, const Eigen::VectorXd& heading, Eigen::Index a,
                            Eigen::Index b, Eigen::Index t, double fps) {
  const double seconds = double(b - a) / fps;
  const double dx = (ground(b, 0) - ground(a, 0)) / seconds, dz = (ground(b, 1) - ground(a, 1)) / seconds;
  const double c = std::cos(heading[t]), s = std::sin(heading[t]);
  return Eigen::Vector2d(c * dx - s * dz, s * dx + c * dz);
}

}  // namespace

void stride_map(const Eigen::MatrixXd& free_ground, const Eigen::VectorXd& free_heading, const Eigen::MatrixXd& ground,
                const Eigen::VectorXd& heading, double fps, double body_height, Eigen::MatrixXd& map) {
  const Eigen::Index samples = ground.rows();
  assert(free_ground.rows() == samples && free_heading.size() == samples && heading.size() == samples);
  map.resize(samples, 4);
  const Eigen::Index half = std::max<Eigen::Index>(1, std::lround(0.5 * kStrideWindowSeconds * fps));
  const double still = kStrideStillSpeed * body_height;
  for (Eigen::Index t = 0; t < samples; ++t) {
    map.row(t) << 1.0, 0.0, 0.0, 1.0;
    const Eigen::Index a = std::max<Eigen::Index>(0, t - half), b = std::min(samples - 1, t + half);
    if (b <= a || !(fps > 0.0)) continue;
    const Eigen::Vector2d v = body_travel(free_ground, free_heading, a, b, t, fps);
    const Eigen::Vector2d w = body_travel(ground, heading, a, b, t, fps);
    // Along the way the free root goes only: across it (a kept heading), a foot mapped sideways
    // is further from its hip. Where the kept root goes faster, the style's steps are shorter than
    // the pace needs and slide by the difference: they are stretched, by at most
    // kStrideLongerLimit, and the foot lock pins the rest. It can, because it changes each run's
    // offset on the swing's slow steps; mid-swing, where the foot is at its fastest, the speed
    // limit would leave it no room.
    // Test: "palette: planted feet of a mix and a transfer move as their takes' do" (mix_palette_test.cpp).
    const double speed = v.norm();
    if (!(speed > 0.0)) continue;
    const Eigen::Vector2d way = v / speed;
    const double kept = std::max(0.0, w.dot(way));
    const double scale = std::min(kStrideLongerLimit, (kept - speed) * speed / (speed * speed + still * still));
    Eigen::Matrix2d change = scale * way * way.transpose();
    const double size = change.norm();
    if (size > kStrideMapLimit) change *= kStrideMapLimit / size;
    map.row(t) << 1.0 + change(0, 0), change(0, 1), change(1, 0), 1.0 + change(1, 1);
  }
}

namespace {

// One flip of `flip` radians at sample r, weighted, spread as add_spread_turns says.
void spread_turn(double flip, Eigen::Index r, double weight, double fps, Eigen::MatrixXd& steps) {
  // What a flip shows is the weight's fraction of a whole turn (weight 1.5 turns by half a turn).
  const double fraction = weight - std::floor(weight);
  const double spread = 4.0 * fraction * (1.0 - fraction);
  const int h = static_cast<int>(std::lround(0.5 * fps * spread));
  const Eigen::Index samples = steps.rows();
  const Eigen::Index width = std::min<Eigen::Index>(2 * h + 1, samples);
  const Eigen::Index first = std::clamp<Eigen::Index>(r - h, 0, samples - width);
  for (Eigen::Index t = first; t < first + width; ++t) steps(t, 2) += weight * flip / double(width);
}

}  // namespace

void add_spread_turns(const Eigen::VectorXd& flips, double weight, double fps, Eigen::MatrixXd& steps) {
  for (Eigen::Index r = 0; r < steps.rows() && r < flips.size(); ++r)
    if (flips[r] != 0.0) spread_turn(flips[r], r, weight, fps, steps);
}

void add_spread_turns(const Eigen::VectorXd& flips, const Eigen::VectorXd& weights, double fps, Eigen::MatrixXd& steps) {
  for (Eigen::Index r = 0; r < steps.rows() && r < flips.size() && r < weights.size(); ++r)
    if (flips[r] != 0.0) spread_turn(flips[r], r, weights[r], fps, steps);
}

}  // namespace mostyle
