#include "engine/canonical_frame.h"

#include <cmath>

#include "engine/error.h"

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

void to_world(const Eigen::MatrixXd& local, const Eigen::MatrixXd& ground,
              const Eigen::VectorXd& heading, Eigen::MatrixXd* world) {
  const Eigen::Index frames = local.rows(), joints = local.cols() / 3;
  world->resize(frames, local.cols());
  for (Eigen::Index t = 0; t < frames; ++t) {
    const double c = std::cos(heading[t]), s = std::sin(heading[t]);
    for (Eigen::Index j = 0; j < joints; ++j) {
      const double x = local(t, 3 * j), z = local(t, 3 * j + 2);
      (*world)(t, 3 * j) = ground(t, 0) + c * x + s * z;
      (*world)(t, 3 * j + 1) = local(t, 3 * j + 1);
      (*world)(t, 3 * j + 2) = ground(t, 1) - s * x + c * z;
    }
  }
}

}  // namespace mostyle
