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
