#include "engine/measure/fastest_joint.h"

#include <catch2/catch.hpp>
#include <vector>

using namespace mostyle;

namespace {

// Two joints over `steps` + 1 frames: joint 0 moves `step` along x each frame, except at the
// steps listed in `jumps` where it moves `jump`; joint 1 stands still.
Eigen::MatrixXd walking_joint(int steps, double step, const std::vector<int>& jumps, double jump) {
  Eigen::MatrixXd world = Eigen::MatrixXd::Zero(steps + 1, 6);
  for (int t = 0; t < steps; ++t) {
    const bool jumped = std::find(jumps.begin(), jumps.end(), t) != jumps.end();
    world(t + 1, 0) = world(t, 0) + (jumped ? jump : step);
  }
  return world;
}

}  // namespace

TEST_CASE("fastest joint: the percentile of the fastest joint's steps, one bad step in a thousand left out") {
  constexpr double fps = 30.0;
  // Two steps of 1 and 2: the nearest rank of 0.999 of two is the second, the faster.
  CHECK(fastest_joint_speed(walking_joint(2, 1.0, {1}, 2.0), fps) == Approx(2.0 * fps));
  // 1001 steps of 1 and one of 10: rank 999 of 0..1000 is still a step of 1.
  CHECK(fastest_joint_speed(walking_joint(1001, 1.0, {500}, 10.0), fps) == Approx(1.0 * fps));
  // Two of 10: ranks 999 and 1000 are theirs.
  CHECK(fastest_joint_speed(walking_joint(1001, 1.0, {3, 500}, 10.0), fps) == Approx(10.0 * fps));
  // Fewer than two frames have no step.
  CHECK(fastest_joint_speed(Eigen::MatrixXd::Zero(1, 6), fps) == 0.0);
  // The scratch form gives the same, its steps one per frame step.
  std::vector<double> steps;
  const Eigen::MatrixXd world = walking_joint(40, 0.5, {7}, 3.0);
  CHECK(fastest_joint_speed(world, fps, steps) == fastest_joint_speed(world, fps));
  CHECK(steps.size() == 40);
}
