#include "engine/decompose/basic_motions.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "engine/base/error.h"
#include "engine/base/job_control.h"
#include "tests/engine/synthetic_motion.h"

using namespace mostyle;
using mostyle::test::synthetic_motion;

namespace {
constexpr double kRelativeExact = 1e-12;  // relative error of identities that hold exactly
}  // namespace

TEST_CASE("basic motions and the residual sum back to the motion", "[basic_motions]") {
  const Eigen::MatrixXd x = synthetic_motion(200, 20, 5, 0.02, 31);
  BasicMotionOptions options;
  options.components = 6;
  options.sparsities = {0.05, 0.1, 0.2};
  const BasicMotions b = decompose_basic_motions(x, options);
  REQUIRE(b.levels.size() == 3);
  REQUIRE(b.residual.rows() == 200);
  REQUIRE(b.residual.cols() == 60);

  Eigen::MatrixXd sum = b.residual;
  for (const Decomposition& level : b.levels) sum += level.weights * level.components;
  CHECK((sum - x).norm() <= kRelativeExact * x.norm());

  // Each level keeps its own sparsity: round(f * 60) non-zeros per component.
  const int keep[] = {3, 6, 12};
  for (int i = 0; i < 3; ++i) {
    CAPTURE(i);
    const Eigen::MatrixXd& c = b.levels[static_cast<size_t>(i)].components;
    REQUIRE(c.rows() == 6);
    for (int r = 0; r < 6; ++r) CHECK((c.row(r).array() != 0.0).count() == keep[i]);
  }

  // Every level removes energy: its objective is at most the energy of what it was given.
  double energy = x.squaredNorm();
  for (const Decomposition& level : b.levels) {
    CHECK(level.objective <= energy);
    CHECK(level.objective < 0.9 * energy);
    energy = level.objective;
  }
  CHECK(b.residual.squaredNorm() == Approx(energy).epsilon(1e-9));
}

TEST_CASE("the first basic motion is the plain decomposition", "[basic_motions]") {
  const Eigen::MatrixXd x = synthetic_motion(120, 10, 3, 0.01, 32);
  BasicMotionOptions options;
  options.components = 4;
  options.sparsities = {0.2, 0.3};
  const BasicMotions b = decompose_basic_motions(x, options);
  const Decomposition d = decompose(x, options.Level(0));
  CHECK(b.levels[0].weights == d.weights);
  CHECK(b.levels[0].components == d.components);
  // The second level decomposes what the first left.
  const Decomposition second = decompose(x - d.weights * d.components, options.Level(1));
  CHECK((b.levels[1].components - second.components).norm() <=
        1e-9 * second.components.norm());
}

TEST_CASE("basic motions reject bad options and honour cancel", "[basic_motions]") {
  const Eigen::MatrixXd x = synthetic_motion(60, 10, 2, 0.01, 33);
  BasicMotionOptions options;
  CHECK_NOTHROW(options.Validate(x));
  options.sparsities = {};
  CHECK_THROWS_AS(decompose_basic_motions(x, options), InputError);
  options.sparsities = {0.1, 1.5};
  CHECK_THROWS_WITH(decompose_basic_motions(x, options), Catch::Contains("level 2"));
  options.sparsities = {0.1};
  options.components = 31;
  CHECK_THROWS_AS(decompose_basic_motions(x, options), InputError);
  options.components = 3;

  JobControl control;
  decompose_basic_motions(x, options, &control);
  CHECK(control.progress.load() == 1.0f);
  control.cancel = true;
  CHECK_THROWS_AS(decompose_basic_motions(x, options, &control), Cancelled);
}
