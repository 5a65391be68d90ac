#include "engine/decompose/decomposition.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "engine/base/error.h"
#include "engine/base/job_control.h"
#include "tests/engine/synthetic_motion.h"

using namespace mostyle;
using mostyle::test::Random;
using mostyle::test::synthetic_motion;

namespace {

constexpr double kMonotoneSlack = 1e-12;  // relative rounding allowed in "never increases"
constexpr double kRelativeExact = 1e-12;  // relative error of identities that hold exactly

// 240 frames of 20 joints driven by 5 limb-like sources, plus a little noise.
Eigen::MatrixXd walk_like(std::uint64_t seed = 1) { return synthetic_motion(240, 20, 5, 0.01, seed); }

int row_nonzeros(const Eigen::MatrixXd& c, int row) {
  return static_cast<int>((c.row(row).array() != 0.0).count());
}

}  // namespace

TEST_CASE("the greedy init factors the most energetic joint", "[decomposition]") {
  // Joint 1 moves along d with signal s(t); joints 0 and 2 stay still. One rank-1 component
  // on joint 1 is exact, with the weight scaled to max |w| = 1.
  const int frames = 50;
  const Eigen::Vector3d direction(1.0, -2.0, 0.5);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(frames, 9);
  Eigen::VectorXd signal(frames);
  for (int f = 0; f < frames; ++f) signal[f] = 3.0 * std::sin(0.2 * f) + 0.5;
  x.middleCols(3, 3) = signal * direction.transpose();

  DecompositionOptions options;
  options.components = 1;
  options.sparsity = 1.0 / 3.0;  // 3 of 9 channels: one joint
  options.max_iterations = 0;
  const Decomposition d = decompose(x, options);
  REQUIRE(d.iterations == 0);
  REQUIRE(d.objective_history.size() == 1);
  CHECK(d.objective < 1e-20);
  CHECK(d.weights.cwiseAbs().maxCoeff() == 1.0);
  CHECK(d.components.leftCols(3).isZero(0.0));
  CHECK(d.components.rightCols(3).isZero(0.0));
  // Component entries are proportional to d, sign fixed so the largest (y, here -2) is positive.
  const Eigen::RowVector3d entries = d.components.middleCols(3, 3);
  const double scale = signal.cwiseAbs().maxCoeff();
  CHECK((entries + scale * direction.transpose()).norm() < 1e-12 * scale);
  CHECK((d.weights.col(0) + signal / scale).norm() < 1e-12);

  // The sign convention holds whatever the eigen solver returns: the largest entry is positive.
  for (const Eigen::Vector3d& dir : {Eigen::Vector3d(-1.0, 2.0, 0.5), Eigen::Vector3d(0.3, 0.2, -1.0),
                                     Eigen::Vector3d(-0.1, -0.2, -1.0), Eigen::Vector3d(4.0, 1.0, 1.0)}) {
    x.middleCols(3, 3) = signal * dir.transpose();
    const Decomposition e = decompose(x, options);
    Eigen::Index largest = 0;
    e.components.row(0).segment(3, 3).cwiseAbs().maxCoeff(&largest);
    CAPTURE(dir.transpose());
    CHECK(e.components(0, 3 + largest) > 0.0);
    CHECK(e.objective < 1e-20);
  }
}

TEST_CASE("decomposition keeps the requested non-zeros and the weight projection",
          "[decomposition]") {
  const Eigen::MatrixXd x = walk_like();
  DecompositionOptions options;  // k = 10, f = 0.1
  const Decomposition d = decompose(x, options);
  REQUIRE(d.weights.rows() == 240);
  REQUIRE(d.weights.cols() == 10);
  REQUIRE(d.components.rows() == 10);
  REQUIRE(d.components.cols() == 60);
  CHECK(options.NonzerosPerComponent(60) == 6);
  for (int c = 0; c < 10; ++c) {
    CAPTURE(c);
    CHECK(row_nonzeros(d.components, c) == 6);
    CHECK(d.weights.col(c).cwiseAbs().maxCoeff() == 1.0);
  }
  CHECK(d.nonzero_fraction == 0.1);
  CHECK(d.objective == Approx((x - d.weights * d.components).squaredNorm()).epsilon(1e-10));
  CHECK(d.rmse == Approx(std::sqrt(d.objective / x.size())));
  CHECK(d.rmse < 0.5 * std::sqrt(x.squaredNorm() / x.size()));
  CHECK(d.elapsed_ms >= 0.0);
  CHECK(d.objective_history.size() == static_cast<size_t>(d.iterations) + 1);
  CHECK(d.objective_history.back() == d.objective);
}

TEST_CASE("sparsity rounds to whole channels per component, at least one", "[decomposition]") {
  DecompositionOptions options;
  options.sparsity = 0.01;
  CHECK(options.NonzerosPerComponent(60) == 1);
  options.sparsity = 0.125;
  CHECK(options.NonzerosPerComponent(60) == 8);  // 7.5 rounds up
  options.sparsity = 1.0;
  CHECK(options.NonzerosPerComponent(60) == 60);

  const Eigen::MatrixXd x = walk_like(3);
  for (double f : {0.01, 0.05, 0.25, 1.0}) {
    options.sparsity = f;
    options.components = 4;
    options.max_iterations = 20;
    const Decomposition d = decompose(x, options);
    const int keep = options.NonzerosPerComponent(60);
    CAPTURE(f, keep);
    for (int c = 0; c < 4; ++c) CHECK(row_nonzeros(d.components, c) == keep);
    CHECK(d.nonzero_fraction == static_cast<double>(keep) / 60.0);
  }
}

TEST_CASE("the decomposition objective never increases over iterations", "[decomposition]") {
  const Eigen::MatrixXd x = walk_like(2);
  for (double f : {0.02, 0.1, 0.5}) {
    DecompositionOptions options;
    options.sparsity = f;
    options.tolerance = 0.0;  // run every iteration
    options.max_iterations = 60;
    const Decomposition d = decompose(x, options);
    CAPTURE(f);
    REQUIRE(d.iterations == 60);
    CHECK_FALSE(d.converged);
    REQUIRE(d.objective_history.size() == 61);
    for (size_t i = 1; i < d.objective_history.size(); ++i) {
      CAPTURE(i);
      CHECK(d.objective_history[i] <= d.objective_history[i - 1] * (1.0 + kMonotoneSlack));
    }
    CHECK(d.objective_history.back() < d.objective_history.front());
  }
}

TEST_CASE("reconstruction error does not grow with more components", "[decomposition]") {
  const Eigen::MatrixXd x = walk_like(4);
  const double noise_floor = 0.01;
  for (double f : {0.1, 0.2}) {
    double previous = std::numeric_limits<double>::infinity();
    for (int k = 1; k <= 12; ++k) {
      DecompositionOptions options;
      options.components = k;
      options.sparsity = f;
      const Decomposition d = decompose(x, options);
      CAPTURE(f, k, d.rmse, previous);
      CHECK(d.rmse <= previous);
      previous = d.rmse;
    }
    // 5 sources of 12 channels each: 60 / (60 f) components cover them, down to the noise.
    CHECK(previous < 1.0 * noise_floor);
  }
}

TEST_CASE("dense components with k = rank reconstruct exactly", "[decomposition]") {
  Random random(9);
  const Eigen::MatrixXd x = random.matrix(120, 4) * random.matrix(4, 30);  // rank 4
  DecompositionOptions options;
  options.components = 4;
  options.sparsity = 1.0;
  options.max_iterations = 500;
  options.tolerance = 1e-14;
  const Decomposition d = decompose(x, options);
  const double scale = std::sqrt(x.squaredNorm() / x.size());
  CAPTURE(d.iterations, d.rmse, scale);
  CHECK(d.rmse < 1e-6 * scale);
  CHECK(d.nonzero_fraction == 1.0);
}

TEST_CASE("at convergence the weights are optimal for the components", "[decomposition]") {
  // The weight update solves min_W ||X - W C||^2 column by column, so once the objective stops
  // moving the gradient with respect to W, -2 (X - W C) C^T, vanishes.
  const Eigen::MatrixXd x = walk_like(7);
  DecompositionOptions options;
  options.max_iterations = 3000;
  options.tolerance = 1e-13;
  const Decomposition d = decompose(x, options);
  const Eigen::MatrixXd gradient = (x - d.weights * d.components) * d.components.transpose();
  CAPTURE(d.iterations);
  CHECK(gradient.norm() < 1e-5 * x.norm() * d.components.norm());
}

TEST_CASE("decomposition is scale-equivariant", "[decomposition]") {
  // Weights are normalized (max |w| = 1) and the stopping rule is relative, so scaling X scales
  // C and nothing else.
  const Eigen::MatrixXd x = walk_like(8);
  DecompositionOptions options;
  options.tolerance = 1e-4;
  const Decomposition unit = decompose(x, options);
  for (double scale : {1e-6, 1e6}) {
    CAPTURE(scale);
    const Decomposition scaled = decompose(scale * x, options);
    CHECK(scaled.iterations == unit.iterations);
    CHECK((scaled.weights - unit.weights).norm() < 1e-9 * unit.weights.norm());
    CHECK((scaled.components - scale * unit.components).norm() <
          1e-9 * scale * unit.components.norm());
  }
}

TEST_CASE("decomposition is deterministic", "[decomposition]") {
  const Eigen::MatrixXd x = walk_like(5);
  const Decomposition first = decompose(x);
  const Decomposition second = decompose(x);
  CHECK(first.weights == second.weights);
  CHECK(first.components == second.components);
  CHECK(first.iterations == second.iterations);
  CHECK(first.objective_history == second.objective_history);
}

TEST_CASE("decomposition stops at the tolerance or the cap", "[decomposition]") {
  const Eigen::MatrixXd x = walk_like(6);
  DecompositionOptions options;
  options.max_iterations = 3;
  options.tolerance = 0.0;
  const Decomposition capped = decompose(x, options);
  CHECK(capped.iterations == 3);
  CHECK_FALSE(capped.converged);

  options.max_iterations = 1000;
  options.tolerance = 1e-3;
  const Decomposition loose = decompose(x, options);
  CHECK(loose.converged);
  CHECK(loose.iterations < 1000);
  const auto& h = loose.objective_history;
  const size_t n = h.size();
  REQUIRE(n >= 2);
  CHECK(std::abs(h[n - 2] - h[n - 1]) < 1e-3 * h[n - 2]);
  if (n >= 3) CHECK(std::abs(h[n - 3] - h[n - 2]) >= 1e-3 * h[n - 3]);
}

TEST_CASE("a motion that does not move decomposes to nothing, without NaN", "[decomposition]") {
  const Eigen::MatrixXd still = Eigen::MatrixXd::Zero(30, 12);
  DecompositionOptions options;
  options.components = 3;
  const Decomposition d = decompose(still, options);
  CHECK(d.objective == 0.0);
  CHECK(d.converged);
  CHECK(d.iterations == 1);
  CHECK(d.weights.allFinite());
  CHECK(d.components.allFinite());
  CHECK((d.weights * d.components).isZero(0.0));
}

TEST_CASE("decomposition rejects invalid options and input", "[decomposition]") {
  const Eigen::MatrixXd x = walk_like();
  DecompositionOptions options;
  CHECK_NOTHROW(options.Validate(x));
  auto rejects = [&](DecompositionOptions o, const Eigen::MatrixXd& m) {
    CHECK_THROWS_AS(o.Validate(m), InputError);
    CHECK_THROWS_AS(decompose(m, o), InputError);
  };
  SECTION("components") {
    options.components = 0;
    rejects(options, x);
    options.components = 61;
    rejects(options, x);
    options.components = 60;
    CHECK_NOTHROW(options.Validate(x));
  }
  SECTION("sparsity") {
    for (double f : {0.0, -0.1, 1.0001, std::nan("")}) {
      options.sparsity = f;
      rejects(options, x);
    }
  }
  SECTION("iterations and tolerance") {
    options.max_iterations = -1;
    rejects(options, x);
    options.max_iterations = 10;
    options.tolerance = -1e-6;
    rejects(options, x);
    options.tolerance = std::numeric_limits<double>::infinity();
    rejects(options, x);
    options.tolerance = 1e-6;
    options.sparse_coding_iterations = 0;
    rejects(options, x);
  }
  SECTION("input") {
    Eigen::MatrixXd bad = x;
    bad(10, 7) = std::nan("");
    rejects(options, bad);
    bad(10, 7) = std::numeric_limits<double>::infinity();
    rejects(options, bad);
    rejects(options, Eigen::MatrixXd(0, 60));
    options.components = 2;
    rejects(options, Eigen::MatrixXd::Ones(10, 7));  // not x, y, z per joint
  }
}

TEST_CASE("decomposition reports progress and honours cancel", "[decomposition]") {
  const Eigen::MatrixXd x = walk_like();
  JobControl control;
  decompose(x, {}, &control);
  CHECK(control.progress.load() == 1.0f);

  control.cancel = true;
  CHECK_THROWS_AS(decompose(x, {}, &control), Cancelled);
  // Cancel is checked per iteration, not before the init: a run without iterations finishes.
  DecompositionOptions init_only;
  init_only.max_iterations = 0;
  CHECK_NOTHROW(decompose(x, init_only, &control));
}

TEST_CASE("shared decomposition of two takes gives one component set and weights per take",
          "[decomposition]") {
  const Eigen::MatrixXd a = synthetic_motion(200, 20, 5, 0.01, 21);
  const Eigen::MatrixXd b = synthetic_motion(150, 20, 5, 0.01, 22);
  DecompositionOptions options;
  const StackedDecomposition s = decompose_stacked({&a, &b}, options);
  REQUIRE(s.weights[0].rows() == 200);
  REQUIRE(s.weights[1].rows() == 150);
  REQUIRE(s.weights[0].cols() == 10);
  REQUIRE(s.weights[1].cols() == 10);
  REQUIRE(s.components.rows() == 10);
  REQUIRE(s.components.cols() == 60);

  // It is exactly the decomposition of the stacked matrix.
  Eigen::MatrixXd stacked(350, 60);
  stacked << a, b;
  const Decomposition d = decompose(stacked, options);
  CHECK(s.components == d.components);
  CHECK(s.weights[0] == d.weights.topRows(200));
  CHECK(s.weights[1] == d.weights.bottomRows(150));
  CHECK(s.iterations == d.iterations);
  CHECK(s.objective == d.objective);
  CHECK(s.nonzero_fraction == 0.1);
  CHECK(s.rmse[0] == Approx(std::sqrt((a - s.weights[0] * s.components).squaredNorm() / a.size())));
  CHECK(s.rmse[1] == Approx(std::sqrt((b - s.weights[1] * s.components).squaredNorm() / b.size())));
  const double total = s.rmse[0] * s.rmse[0] * a.size() + s.rmse[1] * s.rmse[1] * b.size();
  CHECK(total == Approx(s.objective).epsilon(kRelativeExact * 1e3));

  const Eigen::MatrixXd narrow = b.leftCols(57);
  CHECK_THROWS_AS(decompose_stacked({&a, &narrow}, options), InputError);
  Eigen::MatrixXd bad = b;
  bad(0, 0) = std::nan("");
  CHECK_THROWS_WITH(decompose_stacked({&a, &bad}, options), Catch::Contains("take 2"));
}

TEST_CASE("a stacked decomposition of several takes against brute force", "[decomposition]") {
  const Eigen::MatrixXd a = synthetic_motion(60, 6, 3, 0.01, 3), b = synthetic_motion(45, 6, 3, 0.01, 4),
                        c = synthetic_motion(30, 6, 3, 0.01, 5);
  DecompositionOptions o;
  o.components = 4;
  o.sparsity = 0.5;
  const StackedDecomposition s = decompose_stacked({&a, &b, &c}, o);
  REQUIRE(s.weights.size() == 3);
  CHECK(s.weights[0].rows() == 60);
  CHECK(s.weights[1].rows() == 45);
  CHECK(s.weights[2].rows() == 30);
  // Brute force: the one decomposition of the stacked matrix, split by rows.
  Eigen::MatrixXd stacked(135, a.cols());
  stacked << a, b, c;
  const Decomposition d = decompose(stacked, o);
  CHECK((s.components - d.components).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((s.weights[1] - d.weights.middleRows(60, 45)).cwiseAbs().maxCoeff() < 1e-12);
  double objective = 0;
  const Eigen::MatrixXd* takes[] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) {
    const double e = (*takes[i] - s.weights[i] * s.components).squaredNorm();
    objective += e;
    CHECK(s.rmse[i] == Approx(std::sqrt(e / double(takes[i]->size()))));
  }
  CHECK(s.objective == Approx(objective).epsilon(1e-9));
  const Eigen::MatrixXd wrong(10, 9);
  CHECK_THROWS_AS(decompose_stacked({&a, &wrong}, o), InputError);
  CHECK_THROWS_AS(decompose_stacked({}, o), InputError);
}
