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
