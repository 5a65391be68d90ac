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

TEST_CASE("speed limit with bones kept: a child swung round its parent ends nearer the limit than one pass") {
  // At 10 fps: a root standing, a joint 1 above it, and a child 0.5 from that joint turning round
  // it 0.1 radians a frame but 0.8 for six frames (4 units/s against 0.5).
  const int frames = 60;
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(frames, 9);
  double angle = 0.0;
  for (int t = 0; t < frames; ++t) {
    w.block<1, 3>(t, 3) << 0.0, 1.0, 0.0;
    w.block<1, 3>(t, 6) << 0.5 * std::sin(angle), 1.0, 0.5 * std::cos(angle);
    angle += t >= 20 && t < 26 ? 0.8 : 0.1;
  }
  const std::vector<int> parents{-1, 0, 1};
  const std::vector<double> lengths{0.0, 1.0, 0.5};
  const double limit = 2.0;
  Eigen::MatrixXd once = w;
  REQUIRE(limit_joint_speed(once, 10.0, limit, scratch) > 0);
  apply_limb_lengths(once, parents, lengths);
  Eigen::MatrixXd kept = w;
  const int passes = limit_joint_speed_keeping_bones(kept, 10.0, limit, parents, lengths, {}, scratch);
  INFO("one pass: " << fastest_relative(once, 2) << ", " << passes << " passes: " << fastest_relative(kept, 2));
  CHECK(fastest_relative(once, 2) > 1.1 * limit);  // the bone's length gives back what the limit took
  CHECK(passes > 1);
  CHECK(fastest_relative(kept, 2) < fastest_relative(once, 2));
  for (int t = 0; t < frames; ++t)
    CHECK((kept.block<1, 3>(t, 6) - kept.block<1, 3>(t, 3)).norm() == Approx(0.5).epsilon(1e-9));
  // A motion under the limit: no pass changes it.
  Eigen::MatrixXd slow = swing(30, 0.0, 0.1, 5);
  const Eigen::MatrixXd before = slow;
  CHECK(limit_joint_speed_keeping_bones(slow, 10.0, 5.0, {-1, 0, 0}, {0.0, 1.0, 0.5}, {}, scratch) == 0);
  CHECK(slow == before);
}

}  // namespace mostyle
