#include "engine/post/speed_limit.h"

#include <catch2/catch.hpp>
#include <cmath>

namespace mostyle {
namespace {

// Frames x 3 joints at 10 fps: a root walking along x at `root_speed` units/s, a joint 1 above it,
// and a joint 2 swinging along z at 1 unit/s relative to the root but for one step of `jump`.
Eigen::MatrixXd swing(int frames, double root_speed, double jump, int at) {
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(frames, 9);
  double z = 0.0;
  for (int t = 0; t < frames; ++t) {
    const double x = root_speed * t / 10.0;
    w.block<1, 3>(t, 0) << x, 0.0, 0.0;
    w.block<1, 3>(t, 3) << x, 1.0, 0.0;
    w.block<1, 3>(t, 6) << x, 0.5, z;
    z += t == at ? jump : 0.1;
  }
  return w;
}

// The fastest step of joint j relative to the root, units per second at 10 fps.
double fastest_relative(const Eigen::MatrixXd& w, int j) {
  double out = 0.0;
  for (Eigen::Index t = 0; t + 1 < w.rows(); ++t)
    out = std::max(out, ((w.block<1, 3>(t + 1, 3 * j) - w.block<1, 3>(t + 1, 0)) -
                         (w.block<1, 3>(t, 3 * j) - w.block<1, 3>(t, 0))).norm() * 10.0);
  return out;
}

SpeedLimitScratch scratch;

}  // namespace

TEST_CASE("speed limit: a motion under it is left exactly as it is") {
  const Eigen::MatrixXd before = swing(40, 0.0, 0.1, 20);
  Eigen::MatrixXd w = before;
  CHECK(limit_joint_speed(w, 10.0, 1.5, scratch) == 0);
  CHECK(w == before);
  CHECK(limit_joint_speed(w, 10.0, 0.0, scratch) == 0);  // no limit
  CHECK(w == before);
}

TEST_CASE("speed limit: a step over it is spread over its neighbours, the rest untouched") {
  // Joint 2 jumps 0.5 in one step (5 units/s) where it otherwise moves 1 unit/s; the limit 2.
  const Eigen::MatrixXd before = swing(40, 0.0, 0.5, 20);
  Eigen::MatrixXd w = before;
  CHECK(limit_joint_speed(w, 10.0, 2.0, scratch) == 1);
  CHECK(fastest_relative(w, 2) <= 2.0 + 1e-9);
  // The excess (0.3) needs three steps of room (0.1 each) on either side: frames 17..24 move,
  // the others stay (the root and joint 1 everywhere).
  for (int t = 0; t < 40; ++t) {
    INFO("frame " << t);
    CHECK((w.leftCols(6).row(t) - before.leftCols(6).row(t)).norm() == 0.0);
    if (t <= 17 || t >= 24) CHECK((w.row(t) - before.row(t)).norm() < 1e-12);
  }
  CHECK(w(22, 8) > before(22, 8) - 0.5);  // it gets there a little later, by the same path
}

TEST_CASE("speed limit: the root's own speed is kept, the limb's is what is limited") {
  // The root walks at 3 units/s, over a limit of 2.5 for the whole body: joints still relative
  // to it are left alone, and the swinging joint keeps to what the root leaves (none here).
  const Eigen::MatrixXd before = swing(30, 3.0, 0.1, 10);
  Eigen::MatrixXd w = before;
  limit_joint_speed(w, 10.0, 2.5, scratch);
  CHECK((w.leftCols(6) - before.leftCols(6)).cwiseAbs().maxCoeff() == 0.0);
  // The last frame is where it was: a step's excess is moved, never dropped.
  CHECK((w.row(29) - before.row(29)).norm() < 1e-9);
}

}  // namespace mostyle
