#include "engine/trajectory/mixed_root.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "engine/prepare/root_path.h"
#include "tests/engine/synthetic_walker.h"

using namespace mostyle;
using mostyle::test::walk;
using mostyle::test::walk_with_u_turn;

TEST_CASE("integrate_root_towards: A and B exactly at 0 and 1, between them in between", "[mixed_root]") {
  // A walks straight on; B walks the same way but turns back after 40 frames.
  const CanonicalMotion a = to_canonical(walk(100, 0, 0, 0.0, 1.5, [](int) { return 0.0; }), 0, 1, 2);
  const CanonicalMotion b = to_canonical(walk_with_u_turn(0, 0, 0.0), 0, 1, 2);
  const Eigen::MatrixXd steps_a = root_steps(a), steps_b = match_turns(root_steps(b), steps_a);
  Eigen::MatrixXd ground_b;
  Eigen::VectorXd heading_b;
  integrate_root(steps_b, a.ground.row(0).transpose(), a.heading[0], &ground_b, &heading_b);
  Eigen::MatrixXd g, free_g;
  Eigen::VectorXd h, free_h;
  for (double alpha : {0.0, 1.0}) {
    const Eigen::MatrixXd steps = (1 - alpha) * steps_a + alpha * steps_b;
    const Eigen::MatrixXd target = (1 - alpha) * a.ground + alpha * ground_b;
    integrate_root_towards(steps, target, a.heading[0], 30, kRootPullSeconds, &g, &h);
    CHECK((g - (alpha == 0 ? a.ground : ground_b)).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((h - (alpha == 0 ? a.heading : heading_b)).cwiseAbs().maxCoeff() < 1e-9);
  }
  const Eigen::MatrixXd half = 0.5 * (steps_a + steps_b);
  const Eigen::MatrixXd middle = 0.5 * (a.ground + ground_b);  // starts where A does, as B was integrated from there
  integrate_root_towards(half, middle, a.heading[0], 30, 0.0, &free_g, &free_h);
  integrate_root(half, a.ground.row(0).transpose(), a.heading[0], &g, &h);
  CHECK(free_g == g);  // no pull: integrate_root
  integrate_root_towards(half, middle, a.heading[0], 30, kRootPullSeconds, &g, &h);
  CHECK(h == free_h);  // the pull moves the path, not the facing
  // The pulled path stays nearer the middle of A's and B's than the free one.
  const double pulled = (g - middle).rowwise().norm().maxCoeff();
  const double free = (free_g - middle).rowwise().norm().maxCoeff();
  INFO("pulled " << pulled << ", free " << free);
  CHECK(pulled < 0.7 * free);
}

TEST_CASE("keep_near_path: free within half the leash, eased towards it beyond, never past it", "[mixed_root]") {
  // A path along x at 1 a frame, and a root that parts from it sideways by 0.1 a frame.
  const int frames = 40;
  Eigen::MatrixXd path(frames, 2), ground(frames, 2);
  for (int t = 0; t < frames; ++t) {
    path.row(t) << t, 0.0;
    ground.row(t) << t, 0.1 * t;
  }
  const double leash = 2.0;
  Eigen::MatrixXd kept = ground;
  keep_near_path(kept, path, leash);
  for (int t = 0; t < frames; ++t) {
    const double gap = 0.1 * t;
    INFO("frame " << t);
    CHECK(kept(t, 0) == ground(t, 0));  // the gap is sideways: along the path nothing moves
    if (gap <= 1.0) {
      CHECK(kept(t, 1) == ground(t, 1));  // within half the leash, as it was
    } else {
      // Worked by hand: 1 + tanh(gap - 1), half the leash plus the other half eased.
      CHECK(kept(t, 1) == Approx(1.0 + std::tanh(gap - 1.0)).epsilon(1e-12));
      CHECK(kept(t, 1) < leash);
    }
  }
  // The gap's rate of change has no jump where the leash starts to act (slope 1 on both sides).
  for (int t = 1; t + 1 < frames; ++t) CHECK(std::abs((kept(t + 1, 1) - kept(t, 1)) - (kept(t, 1) - kept(t - 1, 1))) < 0.011);
  // No leash: nothing; a path that is the root's: nothing.
  Eigen::MatrixXd same = ground;
  keep_near_path(same, path, 0.0);
  CHECK(same == ground);
  keep_near_path(same, ground, leash);
  CHECK(same == ground);
}

TEST_CASE("remove_path_drift: a gap that grows steadily goes, a sway within the window stays", "[mixed_root]") {
  // A path along x; a root that falls behind it by 0.3 a frame (shorter steps) and sways
  // sideways by 0.5 with a period of 10 frames.
  const int frames = 200, window = 21;
  const double two_pi = 6.28318530717958647692;
  Eigen::MatrixXd path(frames, 2), ground(frames, 2);
  for (int t = 0; t < frames; ++t) {
    path.row(t) << t, 0.0;
    ground.row(t) << 0.7 * t, 0.5 * std::sin(two_pi * t / 10.0);
  }
  Eigen::MatrixXd kept = ground, scratch;
  remove_path_drift(kept, path, window, scratch);
  for (int t = window / 2; t + window / 2 < frames; ++t) {
    INFO("frame " << t);
    // A linear drift is its own centred mean: along the path the gap is gone.
    CHECK(kept(t, 0) == Approx(path(t, 0)).margin(1e-9));
    // Over 21 frames the sway's mean is one period's worth of it: a tenth of its size at most.
    CHECK(std::abs(kept(t, 1) - ground(t, 1)) < 0.06);
  }
  // At the ends the window holds what it can: the gap is still far smaller than it was.
  CHECK(std::abs(kept(frames - 1, 0) - path(frames - 1, 0)) < 0.1 * std::abs(ground(frames - 1, 0) - path(frames - 1, 0)));
  // A window of one sample, or a root on its path: nothing.
  Eigen::MatrixXd same = ground;
  remove_path_drift(same, path, 1, scratch);
  CHECK(same == ground);
  same = path;
  remove_path_drift(same, path, window, scratch);
  CHECK(same == path);
}

TEST_CASE("keep_near_heading: the shorter arc eased as a gap is, across a whole turn too", "[mixed_root]") {
  const double leash = 0.2, pi = 3.14159265358979323846;
  Eigen::VectorXd path(5), heading(5);
  path << 0.0, 0.0, 1.0, pi - 0.05, 0.0;
  // Within half the leash; 0.3 over; 0.3 under; 0.1 over across the turn at pi (the long way
  // round 2 pi - 0.1); a whole turn on, the same facing.
  heading << 0.05, 0.3, 0.7, -pi + 0.05, 2.0 * pi;
  Eigen::VectorXd kept = heading;
  keep_near_heading(kept, path, leash);
  const double eased = 0.1 + 0.1 * std::tanh((0.3 - 0.1) / 0.1);  // worked by hand
  CHECK(kept[0] == heading[0]);
  CHECK(kept[1] == Approx(eased).epsilon(1e-12));
  CHECK(kept[2] == Approx(1.0 - eased).epsilon(1e-12));
  // 0.1 past the path's heading the short way: half the leash, left as it was.
  CHECK(kept[3] == heading[3]);
  CHECK(kept[4] == heading[4]);
  Eigen::VectorXd none = heading;
  keep_near_heading(none, path, 0.0);
  CHECK(none == heading);
}

namespace {

// A root going straight at `speed` per second (body heights 1) in world direction `way` (radians
// from +Z towards +X), facing `facing`, over 61 samples at 30 per second.
void straight(double speed, double way, double facing, Eigen::MatrixXd& ground, Eigen::VectorXd& heading) {
  ground.resize(61, 2);
  heading.setConstant(61, facing);
  for (int t = 0; t < 61; ++t) {
    ground(t, 0) = std::sin(way) * speed * t / 30.0;
    ground(t, 1) = std::cos(way) * speed * t / 30.0;
  }
}

}  // namespace

TEST_CASE("stride_map: the free root's pace to the kept root's, in each one's body frame", "[mixed_root]") {
  Eigen::MatrixXd free_g, kept_g, map;
  Eigen::VectorXd free_h, kept_h;
  // Free at 2 heights per second facing the way it goes, kept at 1: the stride along the way
  // halves, e = 0.1: 1 + (1 - 2) 2 / (4 + 0.01).
  straight(2.0, 0.0, 0.0, free_g, free_h);
  straight(1.0, 0.0, 0.0, kept_g, kept_h);
  stride_map(free_g, free_h, kept_g, kept_h, 30.0, 1.0, map);
  REQUIRE(map.rows() == 61);
  const double half = 1.0 - 2.0 / 4.01;
  for (int t : {0, 30, 60}) {
    CHECK(map(t, 0) == Approx(1.0));
    CHECK(map(t, 1) == Approx(0.0).margin(1e-12));
    CHECK(map(t, 2) == Approx(0.0).margin(1e-12));
    CHECK(map(t, 3) == Approx(half));
  }
  // The kept root going along +X and facing it: the same in its body frame.
  straight(1.0, 0.5 * 3.14159265358979323846, 0.5 * 3.14159265358979323846, kept_g, kept_h);
  stride_map(free_g, free_h, kept_g, kept_h, 30.0, 1.0, map);
  CHECK(map(30, 0) == Approx(1.0));
  CHECK(map(30, 1) == Approx(0.0).margin(1e-12));
  CHECK(map(30, 2) == Approx(0.0).margin(1e-12));
  CHECK(map(30, 3) == Approx(half));
  // Going alike: the identity, exactly. A free root standing still: no stride to fit.
  stride_map(free_g, free_h, free_g, free_h, 30.0, 1.0, map);
  for (int t = 0; t < 61; ++t) CHECK(map.row(t) == Eigen::RowVector4d(1.0, 0.0, 0.0, 1.0));
  straight(0.0, 0.0, 0.0, free_g, free_h);
  stride_map(free_g, free_h, kept_g, kept_h, 30.0, 1.0, map);
  for (int t = 0; t < 61; ++t) CHECK(map.row(t) == Eigen::RowVector4d(1.0, 0.0, 0.0, 1.0));
  // Kept a fifth faster than free: the stride along the way stretched, 1 + (1.2 - 1) 1 / (1 + 0.01);
  // twice as fast: stretched by the limit alone.
  straight(1.0, 0.0, 0.0, free_g, free_h);
  straight(1.2, 0.0, 0.0, kept_g, kept_h);
  stride_map(free_g, free_h, kept_g, kept_h, 30.0, 1.0, map);
  for (int t : {0, 30, 60}) {
    CHECK(map(t, 0) == Approx(1.0));
    CHECK(map(t, 1) == Approx(0.0).margin(1e-12));
    CHECK(map(t, 3) == Approx(1.0 + 0.2 / 1.01));
  }
  straight(2.0, 0.0, 0.0, kept_g, kept_h);
  stride_map(free_g, free_h, kept_g, kept_h, 30.0, 1.0, map);
  for (int t : {0, 30, 60}) CHECK(map(t, 3) == Approx(1.0 + kStrideLongerLimit));
  // Kept at a tenth of the pace, across the way: none of it along the way, the scale held to the limit.
  straight(2.0, 0.0, 0.0, free_g, free_h);
  straight(0.2, 0.5 * 3.14159265358979323846, 0.0, kept_g, kept_h);
  stride_map(free_g, free_h, kept_g, kept_h, 30.0, 1.0, map);
  CHECK(map(30, 3) == Approx(1.0 - kStrideMapLimit));
  CHECK(map.row(30).head<3>() == Eigen::RowVector3d(1.0, 0.0, 0.0));  // across the way: as it was
}
