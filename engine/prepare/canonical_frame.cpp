#include "engine/prepare/canonical_frame.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "engine/base/error.h"

namespace mostyle {
namespace {
constexpr double kDegenerateAxis = 1e-12;  // squared hip-axis length on the ground
}

CanonicalMotion to_canonical(const Eigen::MatrixXd& world, int hips, int left_hip, int right_hip) {
  const Eigen::Index frames = world.rows();
  const Eigen::Index joints = world.cols() / 3;
  CanonicalMotion m;
  m.local.resize(frames, world.cols());
  m.ground.resize(frames, 2);
  m.heading.resize(frames);
  double previous = 0.0;
  bool have_previous = false;
  for (Eigen::Index t = 0; t < frames; ++t) {
    // Forward = (left - right) x up, on the ground: (-r.z, 0, r.x).
    const double rx = world(t, 3 * left_hip) - world(t, 3 * right_hip);
    const double rz = world(t, 3 * left_hip + 2) - world(t, 3 * right_hip + 2);
    double heading = previous;
    if (rx * rx + rz * rz > kDegenerateAxis) {
      heading = std::atan2(-rz, rx);
      if (have_previous) heading += 2 * M_PI * std::round((previous - heading) / (2 * M_PI));
      have_previous = true;
    }
    previous = heading;
    m.heading[t] = heading;
  }
  if (frames > 0 && !have_previous)
    throw InputError("the left and right hips coincide on the ground in every frame; no heading");
  // Frames before the first usable axis take its heading.
  for (Eigen::Index t = 0; t < frames; ++t) {
    const double rx = world(t, 3 * left_hip) - world(t, 3 * right_hip);
    const double rz = world(t, 3 * left_hip + 2) - world(t, 3 * right_hip + 2);
    if (rx * rx + rz * rz > kDegenerateAxis) {
      for (Eigen::Index s = 0; s < t; ++s) m.heading[s] = m.heading[t];
      break;
    }
  }
  for (Eigen::Index t = 0; t < frames; ++t) {
    const double gx = world(t, 3 * hips), gz = world(t, 3 * hips + 2);
    m.ground(t, 0) = gx;
    m.ground(t, 1) = gz;
    const double c = std::cos(m.heading[t]), s = std::sin(m.heading[t]);
    for (Eigen::Index j = 0; j < joints; ++j) {
      const double dx = world(t, 3 * j) - gx, dz = world(t, 3 * j + 2) - gz;
      // R_y(-h) (dx, dz): x' = c dx - s dz, z' = s dx + c dz.
      m.local(t, 3 * j) = c * dx - s * dz;
      m.local(t, 3 * j + 1) = world(t, 3 * j + 1);
      m.local(t, 3 * j + 2) = s * dx + c * dz;
    }
  }
  return m;
}

Eigen::MatrixXd root_steps(const Eigen::MatrixXd& ground, const Eigen::VectorXd& heading) {
  const Eigen::Index frames = ground.rows();
  Eigen::MatrixXd steps = Eigen::MatrixXd::Zero(frames, 3);
  for (Eigen::Index t = 0; t + 1 < frames; ++t) {
    const double dx = ground(t + 1, 0) - ground(t, 0), dz = ground(t + 1, 1) - ground(t, 1);
    const double c = std::cos(heading[t]), s = std::sin(heading[t]);
    steps(t, 0) = c * dx - s * dz;
    steps(t, 1) = s * dx + c * dz;
    steps(t, 2) = heading[t + 1] - heading[t];
  }
  return steps;
}

Eigen::MatrixXd root_steps(const CanonicalMotion& motion) {
  return root_steps(motion.ground, motion.heading);
}

void integrate_root(const Eigen::MatrixXd& steps, const Eigen::Vector2d& start_ground,
                    double start_heading, Eigen::MatrixXd* ground, Eigen::VectorXd* heading) {
  const Eigen::Index frames = steps.rows();
  ground->resize(frames, 2);
  heading->resize(frames);
  if (frames == 0) return;
  (*ground)(0, 0) = start_ground.x();
  (*ground)(0, 1) = start_ground.y();
  (*heading)[0] = start_heading;
  for (Eigen::Index t = 0; t + 1 < frames; ++t) {
    const double c = std::cos((*heading)[t]), s = std::sin((*heading)[t]);
    // R_y(h) (vx, vz): x = c vx + s vz, z = -s vx + c vz.
    (*ground)(t + 1, 0) = (*ground)(t, 0) + c * steps(t, 0) + s * steps(t, 1);
    (*ground)(t + 1, 1) = (*ground)(t, 1) - s * steps(t, 0) + c * steps(t, 1);
    (*heading)[t + 1] = (*heading)[t] + steps(t, 2);
  }
}

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
// Row `at` (fractional, clamped) of x, linearly interpolated.
Eigen::RowVectorXd row_at(const Eigen::MatrixXd& x, double at) {
  const Eigen::Index last = x.rows() - 1;
  const double t = std::clamp(at, 0.0, double(last));
  const Eigen::Index i = std::min<Eigen::Index>(static_cast<Eigen::Index>(t), std::max<Eigen::Index>(last - 1, 0));
  if (last == 0) return x.row(0);
  const double f = t - double(i);
  return (1 - f) * x.row(i) + f * x.row(i + 1);
}
}  // namespace

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

PlacedRoot place_at(const CanonicalMotion& a, double a_frame, const CanonicalMotion& b, double b_frame) {
  if (a.ground.rows() == 0 || b.ground.rows() == 0) throw InputError("cannot place a take without frames");
  const Eigen::RowVectorXd ground_a0 = row_at(a.ground, a_frame);
  const Eigen::RowVectorXd ground_b0 = row_at(b.ground, b_frame);
  const double turn = row_at(a.heading, a_frame)(0) - row_at(b.heading, b_frame)(0);
  const double c = std::cos(turn), s = std::sin(turn);
  PlacedRoot placed;
  placed.ground.resize(b.ground.rows(), 2);
  for (Eigen::Index t = 0; t < b.ground.rows(); ++t) {
    const double x = b.ground(t, 0) - ground_b0(0), z = b.ground(t, 1) - ground_b0(1);
    placed.ground(t, 0) = ground_a0(0) + c * x + s * z;
    placed.ground(t, 1) = ground_a0(1) - s * x + c * z;
  }
  placed.heading = b.heading.array() + turn;
  return placed;
}

Eigen::MatrixXd limit_warped_steps(const Eigen::MatrixXd& steps, const Eigen::VectorXd& warp,
                                   double max_speedup) {
  if (steps.cols() != 3 || steps.rows() != warp.size())
    throw InputError("cannot limit warped root steps: " + std::to_string(steps.rows()) + " x " +
                     std::to_string(steps.cols()) + " steps for a warp of " + std::to_string(warp.size()) +
                     " frames (expected F x 3 and F)");
  Eigen::MatrixXd out = steps;
  for (Eigen::Index t = 0; t + 1 < steps.rows(); ++t) {
    const double skipped = warp[t + 1] - warp[t];
    if (skipped > max_speedup) out.block<1, 2>(t, 0) *= max_speedup / skipped;
  }
  return out;
}

Eigen::MatrixXd match_turns(const Eigen::MatrixXd& steps_b, const Eigen::MatrixXd& steps_a) {
  if (steps_a.rows() != steps_b.rows() || steps_a.cols() != 3 || steps_b.cols() != 3)
    throw InputError("cannot match turns: root steps of " + std::to_string(steps_a.rows()) + " x " +
                     std::to_string(steps_a.cols()) + " and " + std::to_string(steps_b.rows()) + " x " +
                     std::to_string(steps_b.cols()) + " (expected F x 3 both)");
  Eigen::MatrixXd out = steps_b;
  // D = H_B - H_A, both integrated from 0; `whole` turns are taken off B's heading so that
  // |D - 2 pi whole| stays within pi + hysteresis. Changing `whole` at frame t + 1 moves B's turn
  // of step t by the same number of whole turns, which integrate_root cannot tell apart.
  double difference = 0.0;
  double whole = 0.0;
  for (Eigen::Index t = 0; t + 1 < steps_b.rows(); ++t) {
    difference += steps_b(t, 2) - steps_a(t, 2);
    const double wrapped = difference - 2 * M_PI * whole;
    if (std::abs(wrapped) > M_PI + kTurnHysteresis) {
      const double next = std::round(difference / (2 * M_PI));
      out(t, 2) -= 2 * M_PI * (next - whole);
      whole = next;
    }
  }
  return out;
}

void to_world(const Eigen::MatrixXd& local, const Eigen::MatrixXd& ground,
              const Eigen::VectorXd& heading, Eigen::MatrixXd* world) {
  const Eigen::Index frames = local.rows(), joints = local.cols() / 3;
  world->resize(frames, local.cols());
  // Blocks of frames, so that every loop runs down contiguous columns (one frame's values lie a
  // column apart in these column-major matrices); the angles of a block are computed once.
  constexpr Eigen::Index kBlock = 64;
  double c[kBlock], s[kBlock];
  for (Eigen::Index first = 0; first < frames; first += kBlock) {
    const Eigen::Index n = std::min(kBlock, frames - first);
    for (Eigen::Index i = 0; i < n; ++i) {
      c[i] = std::cos(heading[first + i]);
      s[i] = std::sin(heading[first + i]);
    }
    for (Eigen::Index j = 0; j < joints; ++j) {
      const double* x = local.col(3 * j).data() + first;
      const double* y = local.col(3 * j + 1).data() + first;
      const double* z = local.col(3 * j + 2).data() + first;
      const double* gx = ground.col(0).data() + first;
      const double* gz = ground.col(1).data() + first;
      double* wx = world->col(3 * j).data() + first;
      double* wy = world->col(3 * j + 1).data() + first;
      double* wz = world->col(3 * j + 2).data() + first;
      for (Eigen::Index i = 0; i < n; ++i) {
        wx[i] = gx[i] + c[i] * x[i] + s[i] * z[i];
        wy[i] = y[i];
        wz[i] = gz[i] - s[i] * x[i] + c[i] * z[i];
      }
    }
  }
}

}  // namespace mostyle
