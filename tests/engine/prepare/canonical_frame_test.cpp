#include "engine/prepare/canonical_frame.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "engine/base/error.h"
#include "engine/prepare/root_path.h"
#include "tests/engine/synthetic_walker.h"

using namespace mostyle;
using mostyle::test::walk;
using mostyle::test::walk_with_u_turn;

namespace {

constexpr double kExact = 1e-12;      // hand-worked values, to rounding
constexpr double kRoundTrip = 1e-9;   // world -> canonical -> steps -> world, file units

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
