#include "engine/synthesize/synthesis.h"

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "engine/decompose/decomposition.h"
#include "engine/base/error.h"
#include "tests/engine/synthetic_motion.h"

using namespace mostyle;
using mostyle::test::synthetic_motion;

namespace {

constexpr double kRelativeExact = 1e-12;  // identities that hold up to rounding
constexpr double kSvdAgreement = 1e-8;    // two different SVD routes agree to this

double relative_error(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected) {
  return (actual - expected).norm() / expected.norm();
}

// An SVD computed another way than the engine's (eigen-decomposition of C C^T), with the sign
// rule of core_components: each column of V has its largest-magnitude entry positive.
CoreComponents svd_by_hand(const Eigen::MatrixXd& c) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(c * c.transpose());
  const Eigen::Index k = c.rows();
  CoreComponents result;
  result.core.resize(k, k);
  result.basis.resize(c.cols(), k);
  for (Eigen::Index i = 0; i < k; ++i) {
    const Eigen::Index e = k - 1 - i;  // eigenvalues ascend; singular values descend
    const double sigma = std::sqrt(eigen.eigenvalues()[e]);
    Eigen::VectorXd u = eigen.eigenvectors().col(e);
    Eigen::VectorXd v = c.transpose() * u / sigma;
    Eigen::Index largest = 0;
    v.cwiseAbs().maxCoeff(&largest);
    if (v[largest] < 0.0) {
      u = -u;
      v = -v;
    }
    result.core.col(i) = sigma * u;
    result.basis.col(i) = v;
  }
  return result;
}

struct Pair {
  Decomposition a, b;
};

// Two "styles" of the same structure, decomposed separately (paper mode's input).
Pair separate_pair() {
  DecompositionOptions options;
  options.max_iterations = 30;
  return {decompose(synthetic_motion(180, 20, 5, 0.01, 41), options),
          decompose(synthetic_motion(160, 20, 5, 0.01, 42), options)};
}

}  // namespace

TEST_CASE("core components factor C = K V^T with orthonormal V", "[synthesis]") {
  const Pair p = separate_pair();
  const CoreComponents core = core_components(p.a.components);
  REQUIRE(core.core.rows() == 10);
  REQUIRE(core.core.cols() == 10);
  REQUIRE(core.basis.rows() == 60);
  REQUIRE(core.basis.cols() == 10);
  CHECK(relative_error(core.core * core.basis.transpose(), p.a.components) < kRelativeExact);
  CHECK((core.basis.transpose() * core.basis - Eigen::MatrixXd::Identity(10, 10)).norm() <
        kRelativeExact * 10);
  // K = U S: orthogonal columns with decreasing norms (the singular values).
  const Eigen::MatrixXd ktk = core.core.transpose() * core.core;
  CHECK((ktk - Eigen::MatrixXd(ktk.diagonal().asDiagonal())).norm() < 1e-10 * ktk.norm());
  for (int i = 1; i < 10; ++i) CHECK(ktk(i, i) <= ktk(i - 1, i - 1));
  // The sign rule.
  for (int i = 0; i < 10; ++i) {
    Eigen::Index largest = 0;
    core.basis.col(i).cwiseAbs().maxCoeff(&largest);
    CHECK(core.basis(largest, i) > 0.0);
  }
  // Against an SVD computed another way.
  const CoreComponents by_hand = svd_by_hand(p.a.components);
  CHECK(relative_error(core.core, by_hand.core) < kSvdAgreement);
  CHECK(relative_error(core.basis, by_hand.basis) < kSvdAgreement);

  CHECK_THROWS_AS(core_components(Eigen::MatrixXd::Ones(5, 4)), InputError);
  Eigen::MatrixXd bad = p.a.components;
  bad(0, 0) = std::nan("");
  CHECK_THROWS_AS(core_components(bad), InputError);
}

TEST_CASE("paper mode at alpha 0 reproduces W_A C_A", "[synthesis]") {
  const Pair p = separate_pair();
  const PaperSynthesis prepared = prepare_paper_synthesis(
      p.a.weights, core_components(p.a.components), core_components(p.b.components));
  const Eigen::MatrixXd expected = p.a.weights * p.a.components;
  CHECK(relative_error(synthesize_paper(prepared, 0.0), expected) < kRelativeExact);
}

TEST_CASE("paper mode follows W_A((1-a)K_A + a K_B)V_A^T", "[synthesis]") {
  const Pair p = separate_pair();
  const PaperSynthesis prepared = prepare_paper_synthesis(
      p.a.weights, core_components(p.a.components), core_components(p.b.components));
  const CoreComponents a = svd_by_hand(p.a.components);
  const CoreComponents b = svd_by_hand(p.b.components);
  for (double alpha : {0.35, 1.0, 1.5}) {
    CAPTURE(alpha);
    const Eigen::MatrixXd expected =
        p.a.weights * ((1.0 - alpha) * a.core + alpha * b.core) * a.basis.transpose();
    const Eigen::MatrixXd actual = synthesize_paper(prepared, alpha);
    CHECK(relative_error(actual, expected) < kSvdAgreement);
  }
  // Alpha = 1 is not B: the two decompositions' components do not correspond.
  const Eigen::MatrixXd at_one = synthesize_paper(prepared, 1.0);
  CHECK(relative_error(at_one, p.a.weights * p.a.components) > 1e-3);
}

TEST_CASE("basic-motion core swap follows the paper", "[synthesis]") {
  BasicMotionOptions options;
  options.components = 5;
  options.sparsities = {0.1, 0.2, 0.3};
  options.max_iterations = 30;
  const BasicMotions a = decompose_basic_motions(synthetic_motion(120, 20, 5, 0.01, 51), options);
  const BasicMotions b = decompose_basic_motions(synthetic_motion(100, 20, 5, 0.01, 52), options);
  const BasicMotionSynthesis prepared = prepare_basic_motion_synthesis(a, b);

  Eigen::MatrixXd sum_a = Eigen::MatrixXd::Zero(120, 60);
  for (const Decomposition& level : a.levels) sum_a += level.weights * level.components;
  CHECK(relative_error(synthesize_basic_motions(prepared, 1, 0.0), sum_a) < kRelativeExact);

  for (int swap = 0; swap < 3; ++swap) {
    CAPTURE(swap);
    Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(120, 60);
    for (int i = 0; i < 3; ++i) {
      const CoreComponents ka = svd_by_hand(a.levels[static_cast<size_t>(i)].components);
      const CoreComponents kb = svd_by_hand(b.levels[static_cast<size_t>(i)].components);
      const Eigen::MatrixXd& core = i == swap ? kb.core : ka.core;
      expected += a.levels[static_cast<size_t>(i)].weights * core * ka.basis.transpose();
    }
    Eigen::MatrixXd out;
    synthesize_basic_motions(prepared, swap, 1.0, out);
    CHECK(relative_error(out, expected) < kSvdAgreement);
  }
  CHECK_THROWS_AS(synthesize_basic_motions(prepared, 3, 1.0), InputError);
  CHECK_THROWS_AS(synthesize_basic_motions(prepared, -1, 1.0), InputError);

  BasicMotionOptions two = options;
  two.sparsities = {0.1, 0.2};
  const BasicMotions short_b =
      decompose_basic_motions(synthetic_motion(100, 20, 5, 0.01, 52), two);
  CHECK_THROWS_AS(prepare_basic_motion_synthesis(a, short_b), InputError);
}

TEST_CASE("paper mode rejects mismatched cores", "[synthesis]") {
  const Pair p = separate_pair();
  const CoreComponents a = core_components(p.a.components);
  const CoreComponents b = core_components(p.b.components.topRows(9));
  CHECK_THROWS_AS(prepare_paper_synthesis(p.a.weights, a, b), InputError);
  CHECK_THROWS_AS(prepare_paper_synthesis(p.a.weights.leftCols(9), a, a), InputError);
  const PaperSynthesis prepared = prepare_paper_synthesis(p.a.weights, a, a);
  CHECK_THROWS_AS(synthesize_paper(prepared, std::numeric_limits<double>::infinity()),
                  InputError);
}
