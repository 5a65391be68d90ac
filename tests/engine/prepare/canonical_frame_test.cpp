#include "engine/prepare/canonical_frame.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "engine/base/error.h"

using namespace mostyle;

namespace {

constexpr double kExact = 1e-12;      // hand-worked values, to rounding
constexpr double kRoundTrip = 1e-9;   // world -> canonical -> steps -> world, file units

// World positions of a walker with joints hips (0), left hip (1), right hip (2), left foot (3),
// head (4): hips at ground (x, z) and height 90, facing `heading` (0: +Z, pi/2: +X), the left
// foot swinging forward and back with `phase`.
Eigen::RowVectorXd walker(double x, double z, double heading, double phase) {
  const double c = std::cos(heading), s = std::sin(heading);
  // Body frame (right-handed, Y up, facing +Z): left is +X.
  const Eigen::Vector3d local[5] = {{0, 90, 0},
                                    {9, 88, 0},
                                    {-9, 88, 0},
                                    {9, 5 + 3 * std::max(0.0, std::sin(phase)), 20 * std::sin(phase)},
                                    {1, 160, 2}};
  Eigen::RowVectorXd row(15);
  for (int j = 0; j < 5; ++j) {
    // R_y(heading): x = c lx + s lz, z = -s lx + c lz.
    row(3 * j) = x + c * local[j].x() + s * local[j].z();
    row(3 * j + 1) = local[j].y();
    row(3 * j + 2) = z - s * local[j].x() + c * local[j].z();
  }
  return row;
}

// A path of `frames` frames: per frame the walker moves `speed` forward and turns by turn(t).
template <typename Turn>
Eigen::MatrixXd walk(int frames, double x, double z, double heading, double speed, Turn turn) {
  Eigen::MatrixXd world(frames, 15);
  for (int t = 0; t < frames; ++t) {
    world.row(t) = walker(x, z, heading, 0.3 * t);
    x += speed * std::sin(heading);
    z += speed * std::cos(heading);
    heading += turn(t);
  }
  return world;
}

// Walks 40 frames, turns 180 degrees in place (to the left, heading increasing) over 20, walks
// back 40.
Eigen::MatrixXd walk_with_u_turn(double x, double z, double heading, double direction = 1.0) {
  return walk(100, x, z, heading, 1.5, [direction](int t) {
    return t >= 40 && t < 60 ? direction * M_PI / 20 : 0.0;
  });
}

void round_trip(const Eigen::MatrixXd& world) {
  const CanonicalMotion m = to_canonical(world, 0, 1, 2);
  const Eigen::MatrixXd steps = root_steps(m);
  Eigen::MatrixXd ground;
  Eigen::VectorXd heading;
  integrate_root(steps, m.ground.row(0).transpose(), m.heading[0], &ground, &heading);
  CHECK((ground - m.ground).cwiseAbs().maxCoeff() < kRoundTrip);
  CHECK((heading - m.heading).cwiseAbs().maxCoeff() < kRoundTrip);
  Eigen::MatrixXd back;
  to_world(m.local, ground, heading, &back);
  CHECK((back - world).cwiseAbs().maxCoeff() < kRoundTrip);
}

}  // namespace

TEST_CASE("heading and local frame, worked by hand: facing +Z, +X and -Z", "[canonical_frame]") {
  struct Case {
    const char* name;
    double heading;  // radians about +Y
    Eigen::Vector3d left;  // world offset of the left hip from the hips
  };
  // Facing +Z the left hip is at +X; facing +X it is at -Z; facing -Z at -X.
  const Case cases[] = {{"+Z", 0.0, {9, -2, 0}}, {"+X", M_PI / 2, {0, -2, -9}}, {"-Z", M_PI, {-9, -2, 0}}};
  for (const Case& c : cases) {
    INFO("facing " << c.name);
    Eigen::MatrixXd world(1, 12);
    const Eigen::Vector3d hips(3, 90, -4);
    const Eigen::Vector3d forward(std::sin(c.heading), 0, std::cos(c.heading));
    world.block<1, 3>(0, 0) = hips.transpose();
    world.block<1, 3>(0, 3) = (hips + c.left).transpose();
    world.block<1, 3>(0, 6) = (hips - c.left + Eigen::Vector3d(0, -4, 0)).transpose();
    world.block<1, 3>(0, 9) = (hips + 20 * forward + Eigen::Vector3d(0, -85, 0)).transpose();  // a toe ahead
    const CanonicalMotion m = to_canonical(world, 0, 1, 2);
    CHECK(std::remainder(m.heading[0] - c.heading, 2 * M_PI) == Approx(0).margin(kExact));  // -pi is pi
    CHECK(m.ground(0, 0) == 3);
    CHECK(m.ground(0, 1) == -4);
    // Hips on the origin at its height; left hip on +X; the toe straight ahead on +Z.
    CHECK(m.local.block<1, 3>(0, 0).isApprox(Eigen::RowVector3d(0, 90, 0), kExact));
    CHECK((m.local.block<1, 3>(0, 3) - Eigen::RowVector3d(9, 88, 0)).norm() < kExact);
    CHECK((m.local.block<1, 3>(0, 6) - Eigen::RowVector3d(-9, 88, 0)).norm() < kExact);
    CHECK((m.local.block<1, 3>(0, 9) - Eigen::RowVector3d(0, 5, 20)).norm() < kExact);
    Eigen::MatrixXd back;
    to_world(m.local, m.ground, m.heading, &back);
    CHECK((back - world).cwiseAbs().maxCoeff() < kExact);
  }
}

TEST_CASE("root steps, worked by hand", "[canonical_frame]") {
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

TEST_CASE("heading is unwrapped over whole turns", "[canonical_frame]") {
  // Three full turns to the left while walking in a circle.
  const Eigen::MatrixXd world = walk(181, 0, 0, 0, 1.0, [](int) { return 2 * M_PI / 60; });
  const CanonicalMotion m = to_canonical(world, 0, 1, 2);
  for (int t = 0; t < 181; ++t) CHECK(m.heading[t] == Approx(2 * M_PI * t / 60).margin(1e-9));
  // The local pose does not see the turning: the left hip is always at (9, 88, 0).
  for (int t = 0; t < 181; ++t) CHECK((m.local.block<1, 3>(t, 3) - Eigen::RowVector3d(9, 88, 0)).norm() < 1e-9);
  round_trip(world);
}

TEST_CASE("degenerate hip axes", "[canonical_frame]") {
  Eigen::MatrixXd world = walk(10, 0, 0, M_PI / 2, 1.0, [](int) { return 0.0; });
  SECTION("in every frame: an error") {
    // Left and right hip straight above each other.
    for (int t = 0; t < 10; ++t) {
      world.block<1, 3>(t, 3) = world.block<1, 3>(t, 0) + Eigen::RowVector3d(0, 5, 0);
      world.block<1, 3>(t, 6) = world.block<1, 3>(t, 0) - Eigen::RowVector3d(0, 5, 0);
    }
    CHECK_THROWS_AS(to_canonical(world, 0, 1, 2), InputError);
  }
  SECTION("in some frames: the first usable heading before, the previous one after") {
    for (int t : {0, 1, 5}) world.block<1, 3>(t, 6) = world.block<1, 3>(t, 3) + Eigen::RowVector3d(0, -3, 0);
    const CanonicalMotion m = to_canonical(world, 0, 1, 2);
    for (int t = 0; t < 10; ++t) CHECK(m.heading[t] == Approx(M_PI / 2));
  }
  SECTION("no frames") {
    const CanonicalMotion m = to_canonical(Eigen::MatrixXd(0, 15), 0, 1, 2);
    CHECK(m.local.rows() == 0);
    CHECK(m.heading.size() == 0);
  }
}

TEST_CASE("to_canonical, root_steps, integrate_root, to_world give the world back", "[canonical_frame]") {
  SECTION("a 180 degree turn, either way") {
    round_trip(walk_with_u_turn(3, -2, 0.4));
    round_trip(walk_with_u_turn(3, -2, 0.4, -1.0));
  }
  SECTION("walking in opposite directions") {
    round_trip(walk(60, 100, 50, 0.0, 1.2, [](int) { return 0.0; }));
    round_trip(walk(60, -100, -50, M_PI, 1.2, [](int) { return 0.0; }));
  }
  SECTION("facing across the +-pi seam and wandering") {
    round_trip(walk(200, 0, 0, M_PI - 0.1, 1.0, [](int t) { return 0.05 * std::sin(0.07 * t); }));
  }
}

TEST_CASE("takes walking in opposite directions have the same canonical motion", "[canonical_frame]") {
  const Eigen::MatrixXd north = walk(60, 10, 20, 0.0, 1.2, [](int) { return 0.0; });
  const Eigen::MatrixXd south = walk(60, -40, 300, M_PI, 1.2, [](int) { return 0.0; });
  const CanonicalMotion a = to_canonical(north, 0, 1, 2), b = to_canonical(south, 0, 1, 2);
  CHECK((a.local - b.local).cwiseAbs().maxCoeff() < 1e-9);
  CHECK((root_steps(a) - root_steps(b)).cwiseAbs().maxCoeff() < 1e-9);
  // B's steps integrated from A's start walk where A walks.
  Eigen::MatrixXd ground;
  Eigen::VectorXd heading;
  integrate_root(root_steps(b), a.ground.row(0).transpose(), a.heading[0], &ground, &heading);
  CHECK((ground - a.ground).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("limit_warped_steps: no teleport where the warp skips B frames", "[canonical_frame]") {
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

TEST_CASE("match_turns: opposite U-turns blend along the short arc", "[canonical_frame]") {
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

TEST_CASE("match_turns: no change when turns agree, one switch with hysteresis", "[canonical_frame]") {
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

TEST_CASE("integrate_root_towards: A and B exactly at 0 and 1, between them in between", "[canonical_frame]") {
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
