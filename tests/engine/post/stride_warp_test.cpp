#include "engine/post/stride_warp.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "engine/base/error.h"
#include "engine/kinematics/joint_rows.h"

using namespace mostyle;

namespace {

constexpr double kTolerance = 1e-9;

// Columns: left hip, knee, ankle, toe, then the right leg's.
FootRig rig() {
  FootRig r;
  r.legs[0] = {0, 1, 2, 3};
  r.legs[1] = {4, 5, 6, 7};
  r.leg_length = 80.0;
  r.body_height = 100.0;
  r.fps = 30.0;
  return r;
}

// Body frame, facing +z: the left foot a stride ahead (ankle 20 forwards, its knee bent forwards),
// the right foot under its hip. Frames alike.
Eigen::MatrixXd striding(int frames) {
  Eigen::MatrixXd w(frames, 24);
  for (int f = 0; f < frames; ++f) {
    set_joint(w, f, 0, {10.0, 80.0, 0.0});
    set_joint(w, f, 1, {10.0, 42.0, 12.0});
    set_joint(w, f, 2, {10.0, 1.0, 20.0});
    set_joint(w, f, 3, {10.0, 0.0, 28.0});
    set_joint(w, f, 4, {-10.0, 80.0, 0.0});
    set_joint(w, f, 5, {-10.0, 41.0, 2.0});
    set_joint(w, f, 6, {-10.0, 1.0, 0.0});
    set_joint(w, f, 7, {-10.0, 0.0, 8.0});
  }
  return w;
}

Eigen::MatrixXd maps(int frames, double xx, double xz, double zx, double zz) {
  Eigen::MatrixXd m(frames, 4);
  for (int f = 0; f < frames; ++f) m.row(f) << xx, xz, zx, zz;
  return m;
}

double bone(const Eigen::MatrixXd& w, int f, int a, int b) { return (joint_at(w, f, a) - joint_at(w, f, b)).norm(); }

}  // namespace

TEST_CASE("stride warp: the identity leaves every joint where it was") {
  Eigen::MatrixXd w = striding(3);
  const Eigen::MatrixXd before = w;
  warp_strides(w, maps(3, 1.0, 0.0, 0.0, 1.0), rig());
  CHECK(w == before);
}

TEST_CASE("stride warp: a stride halved brings the ankle to half its way ahead, at its height, legs whole") {
  Eigen::MatrixXd w = striding(2);
  const Eigen::MatrixXd before = w;
  Eigen::MatrixXd m = maps(2, 1.0, 0.0, 0.0, 0.5);
  m.row(1) << 1.0, 0.0, 0.0, 1.0;  // frame 1 as it was
  warp_strides(w, m, rig());
  // The left ankle: z 20 -> 10, its height and side kept.
  CHECK(joint_at(w, 0, 2).isApprox(Eigen::Vector3d(10.0, 1.0, 10.0), kTolerance));
  // Thigh, shin and foot keep their lengths; the hip stays; the knee still bends forwards.
  CHECK(bone(w, 0, 0, 1) == Approx(bone(before, 0, 0, 1)).epsilon(kTolerance));
  CHECK(bone(w, 0, 1, 2) == Approx(bone(before, 0, 1, 2)).epsilon(kTolerance));
  CHECK(bone(w, 0, 2, 3) == Approx(bone(before, 0, 2, 3)).epsilon(kTolerance));
  CHECK(joint_at(w, 0, 0) == joint_at(before, 0, 0));
  CHECK(joint_at(w, 0, 1).z() > joint_at(w, 0, 2).z() - 10.0);
  CHECK(joint_at(w, 0, 1).z() > 0.0);
  // The toe ahead of the ankle as it was: the foot keeps its length and pitch (its toe does not
  // tip into the floor), and it points the way it did.
  const Eigen::Vector3d foot = joint_at(w, 0, 3) - joint_at(w, 0, 2);
  CHECK(foot.isApprox(Eigen::Vector3d(0.0, -1.0, 8.0), kTolerance));
  // The right foot, under its hip, moves by its own z only (0): the map keeps it.
  CHECK((joint_at(w, 0, 6) - joint_at(before, 0, 6)).norm() < kTolerance);
  // The other frame: untouched.
  CHECK(w.row(1) == before.row(1));
}

TEST_CASE("stride warp: a map of another size than the poses is refused in a sentence") {
  Eigen::MatrixXd w = striding(3);
  CHECK_THROWS_AS(warp_strides(w, maps(2, 1.0, 0.0, 0.0, 1.0), rig()), InputError);
  CHECK_THROWS_AS(warp_strides(w, Eigen::MatrixXd::Identity(3, 3), rig()), InputError);
}

TEST_CASE("stride warp: a stride stretched past the leg's reach stops there, the foot at its height") {
  // A bent left leg (hip 70 up, knee well forwards) with its ankle 10 ahead, asked to 30 ahead:
  // past its reach (about 74 short of straight, 75 to the target).
  Eigen::MatrixXd w = striding(1);
  set_joint(w, 0, 0, {10.0, 70.0, 0.0});
  set_joint(w, 0, 1, {10.0, 36.0, 20.0});
  set_joint(w, 0, 2, {10.0, 1.0, 10.0});
  set_joint(w, 0, 3, {10.0, 0.0, 18.0});
  const Eigen::MatrixXd before = w;
  warp_strides(w, maps(1, 1.0, 0.0, 0.0, 3.0), rig());
  const Eigen::Vector3d hip = joint_at(w, 0, 0), ankle = joint_at(w, 0, 2);
  const double leg = bone(before, 0, 0, 1) + bone(before, 0, 1, 2);
  CHECK((ankle - hip).norm() == Approx((1.0 - kStrideReachMargin) * leg).epsilon(1e-6));
  CHECK(ankle.y() == Approx(1.0));  // on the floor, not lifted towards the target's direction
  CHECK(ankle.z() > 20.0);          // as far forwards as the leg goes
  CHECK(ankle.z() < 30.0);
  CHECK(bone(w, 0, 0, 1) == Approx(bone(before, 0, 0, 1)).epsilon(kTolerance));
  CHECK(bone(w, 0, 1, 2) == Approx(bone(before, 0, 1, 2)).epsilon(kTolerance));
}

TEST_CASE("stride warp: a leg nearly straight at its heel strike still takes a shorter stride") {
  // The left ankle 20 ahead with the leg within the reach margin of straight: halved, it comes in.
  Eigen::MatrixXd w = striding(1);
  const double leg = bone(w, 0, 0, 1) + bone(w, 0, 1, 2);
  REQUIRE((joint_at(w, 0, 2) - joint_at(w, 0, 0)).norm() > (1.0 - kStrideReachMargin) * leg);
  warp_strides(w, maps(1, 1.0, 0.0, 0.0, 0.5), rig());
  CHECK(joint_at(w, 0, 2).isApprox(Eigen::Vector3d(10.0, 1.0, 10.0), kTolerance));
  // Stretched instead, it stays where it was: it has no reach left.
  Eigen::MatrixXd v = striding(1);
  warp_strides(v, maps(1, 1.0, 0.0, 0.0, 2.0), rig());
  CHECK(joint_at(v, 0, 2).isApprox(Eigen::Vector3d(10.0, 1.0, 20.0), kTolerance));
}

TEST_CASE("stride warp: a foot pointing across the way turns with the map, its length and pitch kept") {
  Eigen::MatrixXd w = striding(1);
  set_joint(w, 0, 3, {16.0, 0.0, 26.0});  // the left toe 6 out and 6 ahead of the ankle, 1 below it
  warp_strides(w, maps(1, 1.0, 0.0, 0.0, 0.5), rig());
  const Eigen::Vector3d foot = joint_at(w, 0, 3) - joint_at(w, 0, 2);
  CHECK(foot.y() == Approx(-1.0));
  CHECK(std::hypot(foot.x(), foot.z()) == Approx(std::hypot(6.0, 6.0)));
  CHECK(foot.z() / foot.x() == Approx(0.5));  // (6, 6) through the map: (6, 3), the way it points
}
