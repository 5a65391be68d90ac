#include "engine/decompose/sparse_coding.h"

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "tests/engine/synthetic_motion.h"

using namespace mostyle;
using mostyle::test::Random;

namespace {

constexpr double kExact = 1e-9;         // planted solutions are recovered to this
constexpr double kObjectiveSlack = 1e-12;  // relative slack when comparing objectives

// All subsets of {0..n-1} with exactly s elements, as index lists.
std::vector<std::vector<int>> subsets(int n, int s) {
  std::vector<std::vector<int>> result;
  for (unsigned mask = 0; mask < (1u << n); ++mask) {
    std::vector<int> subset;
    for (int i = 0; i < n; ++i)
      if (mask & (1u << i)) subset.push_back(i);
    if (static_cast<int>(subset.size()) == s) result.push_back(subset);
  }
  return result;
}

// min 1/2 ||y - D_S x_S||^2 over x_S for one column y and a fixed support S.
double least_squares_on_support(const Eigen::MatrixXd& d, const Eigen::VectorXd& y,
                                const std::vector<int>& support) {
  if (support.empty()) return 0.5 * y.squaredNorm();
  Eigen::MatrixXd ds(d.rows(), static_cast<int>(support.size()));
  for (size_t i = 0; i < support.size(); ++i) ds.col(static_cast<int>(i)) = d.col(support[i]);
  const Eigen::VectorXd x = ds.colPivHouseholderQr().solve(y);
  return 0.5 * (y - ds * x).squaredNorm();
}

int nonzeros(const Eigen::VectorXd& v) { return static_cast<int>((v.array() != 0.0).count()); }

struct Codes {
  Eigen::MatrixXd codes;   // X: atoms x signals
  int iterations = 0;      // passes over X taken
  double objective = 0.0;  // 1/2 ||Y - D X||_F^2 at the returned codes
};

// Sparse codes of y (dims x signals) in d (dims x atoms) from warm_start, through the normal
// equations as the decomposition calls it.
Codes solve_codes(const Eigen::MatrixXd& y, const Eigen::MatrixXd& d, const Eigen::MatrixXd& warm_start,
                  const SparseCodingOptions& options) {
  Codes out;
  out.codes = warm_start;
  out.iterations = sparse_code_normal(d.transpose() * d, d.transpose() * y, out.codes, options);
  out.objective = 0.5 * (y - d * out.codes).squaredNorm();
  return out;
}

}  // namespace

TEST_CASE("keep_largest keeps the largest magnitudes per group, ties to the lower index",
          "[sparse_coding]") {
  std::vector<double> scratch;
  Eigen::MatrixXd x(2, 4);
  x << 1.0, -3.0, 2.0, 0.5,  //
      -2.0, 2.0, 2.0, -2.0;
  Eigen::MatrixXd rows = x;
  keep_largest(rows, 2, SparseGroup::kRow, scratch);
  Eigen::MatrixXd expected_rows(2, 4);
  expected_rows << 0.0, -3.0, 2.0, 0.0,  //
      -2.0, 2.0, 0.0, 0.0;
  CHECK(rows == expected_rows);

  Eigen::MatrixXd columns = x;
  keep_largest(columns, 1, SparseGroup::kColumn, scratch);
  Eigen::MatrixXd expected_columns(2, 4);
  expected_columns << 0.0, -3.0, 2.0, 0.0,  //
      -2.0, 0.0, 0.0, -2.0;
  CHECK(columns == expected_columns);

  Eigen::MatrixXd all = x;
  keep_largest(all, 4, SparseGroup::kRow, scratch);
  CHECK(all == x);
}

TEST_CASE("sparse coding finds a planted sparse solution exactly", "[sparse_coding]") {
  Random random(7);
  const int dims = 30, atoms = 8, signals = 5, s = 2;
  // A well-conditioned dictionary: orthonormal columns, mildly perturbed and rescaled.
  const Eigen::MatrixXd q = random.matrix(dims, atoms).householderQr().householderQ() *
                            Eigen::MatrixXd::Identity(dims, atoms);
  Eigen::MatrixXd d = q + 0.05 * random.matrix(dims, atoms);
  for (int a = 0; a < atoms; ++a) d.col(a) *= 1.0 + 0.2 * a / atoms;
  Eigen::MatrixXd planted = Eigen::MatrixXd::Zero(atoms, signals);
  for (int j = 0; j < signals; ++j) {
    planted((2 * j) % atoms, j) = 1.0 + j;
    planted((2 * j + 3) % atoms, j) = -(2.0 + 0.5 * j);
  }
  const Eigen::MatrixXd y = d * planted;

  SparseCodingOptions options;
  options.nonzeros = s;
  options.max_iterations = 2000;
  options.tolerance = 0.0;
  SECTION("from a cold start") {
    const Codes code = solve_codes(y, d, Eigen::MatrixXd::Zero(atoms, signals), options);
    CHECK((code.codes - planted).cwiseAbs().maxCoeff() < kExact);
    CHECK(code.objective < kExact);
    CHECK(code.iterations == 2000);
  }
  SECTION("from a random warm start") {
    const Codes code = solve_codes(y, d, random.matrix(atoms, signals), options);
    CHECK((code.codes - planted).cwiseAbs().maxCoeff() < kExact);
  }
  SECTION("the tolerance stops it early") {
    options.tolerance = 1e-14;
    const Codes code = solve_codes(y, d, Eigen::MatrixXd::Zero(atoms, signals), options);
    CHECK(code.iterations < 2000);
    CHECK((code.codes - planted).cwiseAbs().maxCoeff() < 1e-6);
  }
}

TEST_CASE("per-column sparse coding never beats the exhaustive optimum and keeps s entries",
          "[sparse_coding]") {
  Random random(11);
  const int dims = 6, atoms = 5, signals = 4;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::MatrixXd d = random.matrix(dims, atoms);
    const Eigen::MatrixXd y = random.matrix(dims, signals);
    for (int s = 1; s <= 3; ++s) {
      double optimum = 0.0;
      for (int j = 0; j < signals; ++j) {
        double best = std::numeric_limits<double>::infinity();
        for (const auto& support : subsets(atoms, s))
          best = std::min(best, least_squares_on_support(d, y.col(j), support));
        optimum += best;
      }
      SparseCodingOptions options;
      options.nonzeros = s;
      options.max_iterations = 500;
      const Codes code = solve_codes(y, d, Eigen::MatrixXd::Zero(atoms, signals), options);
      CAPTURE(trial, s);
      CHECK(code.objective >= optimum * (1.0 - kObjectiveSlack) - 1e-15);
      CHECK(code.objective == Approx(0.5 * (y - d * code.codes).squaredNorm()));
      for (int j = 0; j < signals; ++j) CHECK(nonzeros(code.codes.col(j)) == s);
    }
  }
}

TEST_CASE("per-row sparse coding never beats the exhaustive optimum and keeps s entries per row",
          "[sparse_coding]") {
  Random random(12);
  const int dims = 5, atoms = 2, signals = 3, s = 1;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::MatrixXd d = random.matrix(dims, atoms);
    const Eigen::MatrixXd y = random.matrix(dims, signals);
    // Every choice of one column per row (signals^atoms patterns); for a fixed pattern the
    // problem splits into a least-squares problem per column over the rows allowed there.
    double optimum = std::numeric_limits<double>::infinity();
    for (int first = 0; first < signals; ++first) {
      for (int second = 0; second < signals; ++second) {
        double total = 0.0;
        for (int j = 0; j < signals; ++j) {
          std::vector<int> rows;
          if (first == j) rows.push_back(0);
          if (second == j) rows.push_back(1);
          total += least_squares_on_support(d, y.col(j), rows);
        }
        optimum = std::min(optimum, total);
      }
    }
    SparseCodingOptions options;
    options.nonzeros = s;
    options.group = SparseGroup::kRow;
    options.max_iterations = 500;
    const Codes code = solve_codes(y, d, Eigen::MatrixXd::Zero(atoms, signals), options);
    CAPTURE(trial);
    CHECK(code.objective >= optimum * (1.0 - kObjectiveSlack) - 1e-15);
    for (int a = 0; a < atoms; ++a) CHECK(nonzeros(code.codes.row(a).transpose()) == s);
  }
}

TEST_CASE("sparse coding's objective never increases from a sparse start", "[sparse_coding]") {
  // The 1/||D^T D|| step makes every projected step a majorize-minimize step. The paper's
  // printed 2/||D^T D|| would not: this also fails if the step is doubled.
  Random random(5);
  const Eigen::MatrixXd d = random.matrix(12, 8);
  const Eigen::MatrixXd y = random.matrix(12, 6);
  SparseCodingOptions options;
  options.nonzeros = 3;
  options.max_iterations = 1;
  options.tolerance = 0.0;
  Eigen::MatrixXd codes = Eigen::MatrixXd::Zero(8, 6);
  double previous = 0.5 * y.squaredNorm();
  for (int step = 0; step < 60; ++step) {
    const Codes code = solve_codes(y, d, codes, options);
    CAPTURE(step);
    CHECK(code.objective <= previous * (1.0 + kObjectiveSlack));
    previous = code.objective;
    codes = code.codes;
  }
  CHECK(previous < 0.5 * y.squaredNorm());
}

TEST_CASE("with every atom allowed, sparse coding converges to least squares", "[sparse_coding]") {
  // No sparsity: plain gradient descent on 1/2 ||Y - D X||^2. With the paper's printed step
  // 2/||D^T D|| the error along the top eigenvector would flip sign forever instead.
  Random random(8);
  const Eigen::MatrixXd d = random.matrix(10, 4);
  const Eigen::MatrixXd y = random.matrix(10, 3);
  const Eigen::MatrixXd least_squares = d.colPivHouseholderQr().solve(y);
  SparseCodingOptions options;
  options.nonzeros = 4;
  options.max_iterations = 5000;
  options.tolerance = 0.0;
  const Codes code = solve_codes(y, d, Eigen::MatrixXd::Zero(4, 3), options);
  CHECK((code.codes - least_squares).norm() < 1e-8 * least_squares.norm());
  // Per-row budgets of every signal are the same problem, solved by row blocks.
  options.group = SparseGroup::kRow;
  options.nonzeros = 3;
  const Codes rows = solve_codes(y, d, Eigen::MatrixXd::Zero(4, 3), options);
  CHECK((rows.codes - least_squares).norm() < 1e-8 * least_squares.norm());
}
