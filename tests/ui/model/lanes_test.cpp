// Side by side as parallel lanes: takes keep their poses and stand beside the result's path.
#include "ui/model/lanes.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace mostyle::ui;

namespace {
// K frames of two joints: the hips at (x, 1, z), a hand 0.5 to its left and 0.2 up.
Eigen::MatrixXd walk(int frames, double x0, double dx, double dz) {
  Eigen::MatrixXd w(frames, 6);
  for (int t = 0; t < frames; ++t) {
    w.row(t) << x0 + dx * t, 1.0, dz * t, x0 + dx * t - 0.5, 1.2, dz * t;
  }
  return w;
}
}  // namespace

TEST_CASE("lanes: a take that drifts away walks in its lane beside the result") {
  const Eigen::MatrixXd result = walk(100, 0.0, 0.0, 0.1);      // straight along +z
  const Eigen::MatrixXd drifting = walk(100, 0.0, 0.05, 0.1);   // drifts 5 units to +x over the take
  const Lanes lanes = lanes_along(result, Eigen::Vector2d(1.0, 0.0));
  for (Eigen::Index t = 0; t < 100; ++t) {
    CHECK(lanes.across(t, 0) == Approx(1.0));  // to the right of travel along +z is +x
    CHECK(lanes.across(t, 1) == Approx(0.0).margin(1e-12));
  }
  Eigen::MatrixXd placed;
  place_in_lane(drifting, lanes, -2.0, Eigen::Vector3d(0.0, -1.0, 0.0), placed);
  for (Eigen::Index t = 0; t < 100; ++t) {
    CHECK(placed(t, 0) == Approx(-2.0));             // hips on the lane, 2 units across
    CHECK(placed(t, 2) == Approx(result(t, 2)));     // level with the result
    CHECK(placed(t, 1) == Approx(0.0));              // the shift applies
    CHECK(placed(t, 3) - placed(t, 0) == Approx(-0.5));  // the pose is kept
    CHECK(placed(t, 4) - placed(t, 1) == Approx(0.2));
  }
}

TEST_CASE("lanes: a result standing still keeps the fallback direction") {
  const Eigen::MatrixXd still = walk(10, 3.0, 0.0, 0.0);
  const Lanes lanes = lanes_along(still, Eigen::Vector2d(0.0, 2.0));
  for (Eigen::Index t = 0; t < 10; ++t) {
    CHECK(lanes.across(t, 0) == Approx(0.0).margin(1e-12));
    CHECK(lanes.across(t, 1) == Approx(1.0));
  }
}
