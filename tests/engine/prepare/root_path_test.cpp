#include "engine/prepare/root_path.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "engine/base/error.h"
#include "tests/engine/synthetic_walker.h"

using namespace mostyle;
using mostyle::test::walk_with_u_turn;

namespace {
constexpr double kExact = 1e-12;  // hand-worked values, to rounding
}  // namespace

TEST_CASE("root steps, worked by hand", "[root_path]") {
  // Facing +X (heading pi/2) and moving 2 along +X while turning by +pi/2 to face -Z (heading pi),
  // then moving 1 along -Z.
  Eigen::MatrixXd ground(3, 2);
  ground << 0, 0, 2, 0, 2, -1;
  Eigen::VectorXd heading(3);
  heading << M_PI / 2, M_PI, M_PI;
  const Eigen::MatrixXd steps = root_steps(ground, heading);
  // Step 0: 2 forward in a frame facing +X; step 1: 1 along -Z, forward when facing -Z.
  CHECK((steps.row(0) - Eigen::RowVector3d(0, 2, M_PI / 2)).norm() < kExact);
  CHECK((steps.row(1) - Eigen::RowVector3d(0, 1, 0)).norm() < kExact);
  CHECK(steps.row(2).isZero());  // the last row is zero
  Eigen::MatrixXd g;
  Eigen::VectorXd h;
  integrate_root(steps, Eigen::Vector2d(0, 0), M_PI / 2, &g, &h);
  CHECK((g - ground).cwiseAbs().maxCoeff() < kExact);
  CHECK((h - heading).cwiseAbs().maxCoeff() < kExact);
  // A sidestep to the left: facing +Z, moving +X is vx = +1.
  Eigen::MatrixXd side(2, 2);
  side << 0, 0, 1, 0;
  CHECK((root_steps(side, Eigen::VectorXd::Zero(2)).row(0) - Eigen::RowVector3d(1, 0, 0)).norm() < kExact);
  // Empty and one-frame inputs.
  CHECK(root_steps(Eigen::MatrixXd(0, 2), Eigen::VectorXd(0)).rows() == 0);
  CHECK(root_steps(Eigen::MatrixXd::Ones(1, 2), Eigen::VectorXd::Ones(1)).isZero());
  integrate_root(Eigen::MatrixXd(0, 3), Eigen::Vector2d(1, 1), 0.0, &g, &h);
  CHECK(g.rows() == 0);
}

TEST_CASE("limit_warped_steps: no teleport where the warp skips B frames", "[root_path]") {
  Eigen::MatrixXd steps(4, 3);
  steps << 0, 1, 0.1, 3, 4, 0.2, 0, 3, 0.3, 0, 0, 0;
  Eigen::VectorXd warp(4);
  warp << 0, 1, 9, 10.5;  // B runs over 1, 8 and 1.5 frames
  const Eigen::MatrixXd limited = limit_warped_steps(steps, warp, 4.0);
  Eigen::MatrixXd expected = steps;
  expected.block<1, 2>(1, 0) << 1.5, 2;  // 4 of 8 frames: half the way, the whole turn
  CHECK(limited == expected);
  CHECK(limit_warped_steps(steps, warp, 10.0) == steps);
  CHECK_THROWS_AS(limit_warped_steps(steps, Eigen::VectorXd::Zero(3), 4.0), InputError);
  CHECK_THROWS_AS(limit_warped_steps(Eigen::MatrixXd::Zero(4, 2), warp, 4.0), InputError);
}

TEST_CASE("match_turns: opposite U-turns blend along the short arc", "[root_path]") {
  // A turns back to the left, B to the right, at the same time.
  const CanonicalMotion a = to_canonical(walk_with_u_turn(0, 0, 0.0, 1.0), 0, 1, 2);
  const CanonicalMotion b = to_canonical(walk_with_u_turn(0, 0, 0.0, -1.0), 0, 1, 2);
  const Eigen::MatrixXd steps_a = root_steps(a), steps_b = root_steps(b);
  const Eigen::MatrixXd matched = match_turns(steps_b, steps_a);
  // Only turns change, and only by whole turns.
  CHECK(matched.leftCols(2) == steps_b.leftCols(2));
  const Eigen::VectorXd change = (matched.col(2) - steps_b.col(2)) / (2 * M_PI);
  CHECK((change.array() - change.array().round()).abs().maxCoeff() < kExact);
  CHECK(change.cwiseAbs().sum() == Approx(1.0));
  // B's path and facing are unchanged.
  Eigen::MatrixXd g_b, g_m;
  Eigen::VectorXd h_b, h_m;
  integrate_root(steps_b, Eigen::Vector2d::Zero(), 0.0, &g_b, &h_b);
  integrate_root(matched, Eigen::Vector2d::Zero(), 0.0, &g_m, &h_m);
  CHECK((g_m - g_b).cwiseAbs().maxCoeff() < 1e-9);
  for (int t = 0; t < h_b.size(); ++t) CHECK(std::remainder(h_m[t] - h_b[t], 2 * M_PI) == Approx(0).margin(1e-9));
  // Its heading stays within pi + hysteresis of A's.
  Eigen::MatrixXd g_a;
  Eigen::VectorXd h_a;
  integrate_root(steps_a, Eigen::Vector2d::Zero(), 0.0, &g_a, &h_a);
  CHECK((h_m - h_a).cwiseAbs().maxCoeff() <= M_PI + kTurnHysteresis + 1e-9);
  // Both end up facing -Z; the half blend does too, not +Z (unmatched, the turns cancel out).
  const Eigen::MatrixXd half_unmatched = 0.5 * (steps_a + steps_b), half = 0.5 * (steps_a + matched);
  Eigen::MatrixXd g;
  Eigen::VectorXd h;
  integrate_root(half_unmatched, Eigen::Vector2d::Zero(), 0.0, &g, &h);
  CHECK(std::cos(h[99]) == Approx(1.0));
  integrate_root(half, Eigen::Vector2d::Zero(), 0.0, &g, &h);
  CHECK(std::cos(h[99]) == Approx(-1.0));
}

TEST_CASE("match_turns: no change when turns agree, one switch with hysteresis", "[root_path]") {
  const Eigen::MatrixXd a = root_steps(to_canonical(walk_with_u_turn(0, 0, 0.0), 0, 1, 2));
  CHECK(match_turns(a, a) == a);
  // A does not turn. B turns to face backwards, wobbles by 0.3 rad across pi for a while, then
  // turns on: the arc changes sides once, when the gap passes pi + hysteresis, not at every wobble.
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(200, 3), flat = Eigen::MatrixXd::Zero(200, 3);
  double previous = 0;
  for (int t = 0; t < 200; ++t) {
    double target = t < 20 ? M_PI * t / 20 : M_PI + 0.3 * std::sin(0.3 * (t - 20));
    if (t >= 150) target += (t - 150) * 0.03;
    if (t > 0) b(t - 1, 2) = target - previous;
    previous = target;
  }
  const Eigen::MatrixXd matched = match_turns(b, flat);
  int switches = 0;
  for (int t = 0; t < 200; ++t) switches += matched(t, 2) != b(t, 2);
  CHECK(switches == 1);
  CHECK_THROWS_AS(match_turns(b, Eigen::MatrixXd::Zero(10, 3)), InputError);
  CHECK_THROWS_AS(match_turns(Eigen::MatrixXd::Zero(10, 2), Eigen::MatrixXd::Zero(10, 2)), InputError);
}
