#include "engine/align/slope_dtw.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "engine/base/error.h"
#include "engine/base/job_control.h"
#include "tests/engine/synthetic_motion.h"

using namespace mostyle;
using mostyle::test::random_series;
using mostyle::test::Random;

namespace {

using Steps = std::vector<std::pair<int, int>>;

// Costs are sums of a few dozen rounded distances added in different orders.
constexpr double kCostTolerance = 1e-9;  // relative
constexpr double kCostMargin = 1e-12;    // absolute, for optima of (nearly) zero
constexpr double kInf = std::numeric_limits<double>::infinity();
// Frames of the padding in b an open-ended path may still take in: "a couple".
constexpr int kPaddingSlack = 3;

double c(const Eigen::MatrixXd& a, int i, const Eigen::MatrixXd& b, int j) { return (a.row(i) - b.row(j)).norm(); }

// The cost of one step from (i0, j0) to (i1, j1) as the header defines it, written
// independently of slope_dtw.cpp: a (1, k) step passes (i1, j0 + 1) .. (i1, j1) and costs
// 2 c(i1, j0 + 1) + c(i1, j0 + 2) + ... + c(i1, j1); a (k, 1) step likewise down the column.
double step_cost(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, int i0, int j0, int i1, int j1) {
  double sum = 0.0;
  if (i1 - i0 == 1) {
    for (int j = j0 + 1; j <= j1; ++j) sum += (j == j0 + 1 ? 2.0 : 1.0) * c(a, i1, b, j);
  } else {
    for (int i = i0 + 1; i <= i1; ++i) sum += (i == i0 + 1 ? 2.0 : 1.0) * c(a, i, b, j1);
  }
  return sum;
}

bool allowed_step(int di, int dj, int max_slope) {
  return (di == 1 && dj >= 1 && dj <= max_slope) || (dj == 1 && di >= 1 && di <= max_slope);
}

// The weighted cost of a path's vertices: 2 c at the start plus each step's cost.
double path_cost(const Steps& steps, const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  double sum = 2.0 * c(a, steps.front().first, b, steps.front().second);
  for (size_t k = 1; k < steps.size(); ++k)
    sum += step_cost(a, b, steps[k - 1].first, steps[k - 1].second, steps[k].first, steps[k].second);
  return sum;
}

int left_out(const Steps& steps, int n, int m) {
  return (n - (steps.back().first - steps.front().first + 1)) + (m - (steps.back().second - steps.front().second + 1));
}

// Every path there is, enumerated depth first from every allowed start: the smallest objective
// (cost + penalty per frame left out; closed ends: (0, 0) to (n-1, m-1) only). +inf when no
// path connects.
class BruteForce {
 public:
  BruteForce(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, int max_slope, bool open, double penalty)
      : a_(a), b_(b), n_(static_cast<int>(a.rows())), m_(static_cast<int>(b.rows())), s_(max_slope), open_(open),
        penalty_(penalty) {}

  double optimum() {
    best_ = kInf;
    for (int i = 0; i < n_; ++i)
      for (int j = 0; j < m_; ++j)
        if (open_ || (i == 0 && j == 0)) walk(i, j, i, j, 2.0 * c(a_, i, b_, j));
    return best_;
  }

 private:
  void walk(int i0, int j0, int i, int j, double cost) {
    if (open_) {
      const int covered = (i - i0 + 1) + (j - j0 + 1);
      best_ = std::min(best_, cost + penalty_ * (n_ + m_ - covered));
    } else if (i == n_ - 1 && j == m_ - 1) {
      best_ = std::min(best_, cost);
    }
    for (int di = 1; di <= s_; ++di)
      for (int dj = 1; dj <= s_; ++dj) {
        if (!allowed_step(di, dj, s_) || i + di >= n_ || j + dj >= m_) continue;
        walk(i0, j0, i + di, j + dj, cost + step_cost(a_, b_, i, j, i + di, j + dj));
      }
  }

  const Eigen::MatrixXd& a_;
  const Eigen::MatrixXd& b_;
  int n_, m_, s_;
  bool open_;
  double penalty_;
  double best_ = kInf;
};

// The path's vertices lie in the grid, advance by allowed steps, and its cost and objective
// are what the header's definition gives for them.
void check_path(const SlopeDtwPath& path, const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, int max_slope,
                bool open) {
  const int n = static_cast<int>(a.rows()), m = static_cast<int>(b.rows());
  REQUIRE(!path.steps.empty());
  for (size_t k = 0; k < path.steps.size(); ++k) {
    const auto [i, j] = path.steps[k];
    REQUIRE((i >= 0 && i < n && j >= 0 && j < m));
    if (k == 0) continue;
    const int di = i - path.steps[k - 1].first, dj = j - path.steps[k - 1].second;
    INFO("vertex " << k << ": (" << path.steps[k - 1].first << ", " << path.steps[k - 1].second << ") to (" << i
                   << ", " << j << ")");
    REQUIRE(allowed_step(di, dj, max_slope));
  }
  if (!open) {
    CHECK(path.steps.front() == std::make_pair(0, 0));
    CHECK(path.steps.back() == std::make_pair(n - 1, m - 1));
  }
  const double cost = path_cost(path.steps, a, b);
  CHECK(path.cost == Approx(cost).epsilon(kCostTolerance).margin(kCostMargin));
  const double penalty = open ? path.end_penalty : 0.0;
  CHECK(path.objective ==
        Approx(cost + penalty * left_out(path.steps, n, m)).epsilon(kCostTolerance).margin(kCostMargin));
}

Eigen::MatrixXd column(std::initializer_list<double> values) {
  Eigen::MatrixXd x(static_cast<Eigen::Index>(values.size()), 1);
  Eigen::Index i = 0;
  for (double v : values) x(i++, 0) = v;
  return x;
}


Steps diagonal(int n) {
  Steps s;
  for (int i = 0; i < n; ++i) s.emplace_back(i, i);
  return s;
}

// A walk's feature at fractional frame t: a cycle of `period` frames (two harmonics, so no two
// phases look alike).
Eigen::RowVector3d walk_pose(double t, double period) {
  const double phase = 2.0 * M_PI * t / period;
  return {std::sin(phase), std::cos(phase), 0.5 * std::sin(2.0 * phase)};
}

}  // namespace

TEST_CASE("slope dtw: identical series match along the diagonal", "[slope_dtw]") {
  const Eigen::MatrixXd a = column({0, 1, 4, 9, 16, 25, 36, 49});  // distinct values: one zero-cost path
  const int n = static_cast<int>(a.rows());
  SlopeDtwOptions open, closed;
  closed.open_ends = false;
  for (const SlopeDtwOptions& o : {open, closed}) {
    INFO("open ends " << o.open_ends);
    const SlopeDtwPath path = align_slope_dtw(a, a, o);
    CHECK(path.steps == diagonal(n));
    CHECK(path.cost == 0.0);
    CHECK(path.objective == 0.0);
  }
  // Automatic penalty: within its bounds of the random-phase median.
  const SlopeDtwPath path = align_slope_dtw(a, a, open);
  const double random = median_pair_cost(a, a);
  CHECK(random > 0);
  CHECK(path.end_penalty >= kEndPenaltyMin * random);
  CHECK(path.end_penalty <= kEndPenaltyMax * random);
}

TEST_CASE("slope dtw: a series and its 2x slowed copy match in slope-2 steps", "[slope_dtw]") {
  // a_i = i, b_j = j / 2 (9 frames for a's 5). From (0, 0) to (4, 8) in 4 steps that each
  // advance a by at least one, every step must be (1, 2). Each passes (i, 2i-1) at distance 1/2
  // (counted twice, the step's first cell) and (i, 2i) at 0: cost 1 per step, 4 in all.
  const Eigen::MatrixXd a = column({0, 1, 2, 3, 4});
  const Eigen::MatrixXd b = column({0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4});
  const Steps expected = {{0, 0}, {1, 2}, {2, 4}, {3, 6}, {4, 8}};
  SlopeDtwOptions closed;
  closed.open_ends = false;
  SlopeDtwOptions open;
  open.end_penalty = 10.0;  // leaving out any frame costs more than the whole match
  for (const SlopeDtwOptions& o : {closed, open}) {
    INFO("open ends " << o.open_ends);
    const SlopeDtwPath path = align_slope_dtw(a, b, o);
    CHECK(path.steps == expected);
    CHECK(path.cost == Approx(4.0).epsilon(kCostTolerance));
    CHECK(path.objective == Approx(4.0).epsilon(kCostTolerance));
  }
  // Swapped, the path is transposed: (2, 1) steps.
  Steps transposed;
  for (const auto& [i, j] : expected) transposed.emplace_back(j, i);
  CHECK(align_slope_dtw(b, a, closed).steps == transposed);
}

TEST_CASE("slope dtw: open ends leave out frames that match worse than the penalty", "[slope_dtw]") {
  // b = a with a frame of 9 added at each end. Matching a 9 costs at least 2 x 7 (a start
  // counts twice); leaving it out costs the penalty of 1. The zero-cost diagonal through
  // b's frames 1..3 leaves out two frames: objective 2.
  const Eigen::MatrixXd a = column({0, 1, 2}), b = column({9, 0, 1, 2, 9});
  SlopeDtwOptions o;
  o.end_penalty = 1.0;
  const SlopeDtwPath path = align_slope_dtw(a, b, o);
  CHECK(path.steps == Steps{{0, 1}, {1, 2}, {2, 3}});
  CHECK(path.cost == 0.0);
  CHECK(path.end_penalty == 1.0);
  CHECK(path.objective == 2.0);
}

TEST_CASE("slope dtw: the objective equals brute force over every allowed path", "[slope_dtw]") {
  Random random(20250811);
  int trials = 0, refused = 0;
  for (int max_slope : {2, 3}) {
    for (int trial = 0; trial < 150; ++trial) {
      const int n = 1 + static_cast<int>(7 * random.uniform()), m = 1 + static_cast<int>(7 * random.uniform());
      const int d = 1 + static_cast<int>(2 * random.uniform());
      const Eigen::MatrixXd a = random_series(random, n, d), b = random_series(random, m, d);
      const double fixed_penalty = 0.2 + 2.0 * random.uniform();
      INFO("slope " << max_slope << ", trial " << trial << ": " << n << " x " << m << ", d " << d);

      // Closed ends.
      SlopeDtwOptions closed;
      closed.max_slope = max_slope;
      closed.open_ends = false;
      const double closed_optimum = BruteForce(a, b, max_slope, false, 0.0).optimum();
      if (closed_optimum == kInf) {
        CHECK_THROWS_AS(align_slope_dtw(a, b, closed), InputError);
        ++refused;
      } else {
        const SlopeDtwPath path = align_slope_dtw(a, b, closed);
        check_path(path, a, b, max_slope, false);
        CHECK(path.objective == Approx(closed_optimum).epsilon(kCostTolerance).margin(kCostMargin));
      }

      // Open ends with a given penalty.
      SlopeDtwOptions open;
      open.max_slope = max_slope;
      open.end_penalty = fixed_penalty;
      const SlopeDtwPath fixed = align_slope_dtw(a, b, open);
      INFO("penalty " << fixed_penalty);
      CHECK(fixed.end_penalty == fixed_penalty);
      check_path(fixed, a, b, max_slope, true);
      const double open_optimum = BruteForce(a, b, max_slope, true, fixed_penalty).optimum();
      CHECK(fixed.objective == Approx(open_optimum).epsilon(kCostTolerance).margin(kCostMargin));

      // Open ends with the automatic penalty: optimal for the penalty it settled on.
      open.end_penalty = -1.0;
      const SlopeDtwPath automatic = align_slope_dtw(a, b, open);
      check_path(automatic, a, b, max_slope, true);
      const double median = median_pair_cost(a, b);
      CHECK(automatic.end_penalty >= kEndPenaltyMin * median - kCostMargin);
      CHECK(automatic.end_penalty <= kEndPenaltyMax * median + kCostMargin);
      CHECK(automatic.objective == Approx(BruteForce(a, b, max_slope, true, automatic.end_penalty).optimum())
                                       .epsilon(kCostTolerance)
                                       .margin(kCostMargin));
      ++trials;
    }
  }
  CHECK(trials == 300);
  CHECK(refused > 20);  // closed ends that cannot connect are really exercised
}

TEST_CASE("slope dtw: every step of a longer path is allowed", "[slope_dtw]") {
  Random random(5);
  const Eigen::MatrixXd a = random_series(random, 60, 3), b = random_series(random, 45, 3);
  for (int max_slope : {2, 3, 4}) {
    for (bool open : {true, false}) {
      INFO("slope " << max_slope << ", open " << open);
      SlopeDtwOptions o;
      o.max_slope = max_slope;
      o.open_ends = open;
      check_path(align_slope_dtw(a, b, o), a, b, max_slope, open);
    }
  }
}

TEST_CASE("slope dtw: checkpointed traceback gives the one-pass path exactly", "[slope_dtw]") {
  Random random(77);
  const Eigen::MatrixXd a = random_series(random, 60, 3), b = random_series(random, 45, 3);
  for (int max_slope : {2, 3}) {
    for (bool open : {true, false}) {
      // 1 byte: segments of max_slope rows; 100 bytes: 4 rows of 23 bytes.
      for (std::size_t budget : {std::size_t{1}, std::size_t{100}}) {
        INFO("slope " << max_slope << ", open " << open << ", budget " << budget);
        SlopeDtwOptions one_pass, checkpointed;
        one_pass.max_slope = checkpointed.max_slope = max_slope;
        one_pass.open_ends = checkpointed.open_ends = open;
        checkpointed.pointer_budget_bytes = budget;
        const SlopeDtwPath x = align_slope_dtw(a, b, one_pass), y = align_slope_dtw(a, b, checkpointed);
        CHECK(y.steps == x.steps);
        CHECK(y.cost == x.cost);
        CHECK(y.objective == x.objective);
        CHECK(y.end_penalty == x.end_penalty);
      }
    }
  }
}

TEST_CASE("slope dtw: open ends match a walk and leave out standing before and after it", "[slope_dtw]") {
  // a: three cycles of a walk. b: the same walk 1.2 times slower, with 20 frames standing in its
  // first pose before and 20 in its last pose after.
  constexpr double kPeriod = 30.0, kSlower = 1.2;
  constexpr int kWalkA = 90, kWalkB = 108, kPad = 20;
  Eigen::MatrixXd a(kWalkA, 3), b(kWalkB + 2 * kPad, 3);
  for (int t = 0; t < kWalkA; ++t) a.row(t) = walk_pose(t, kPeriod);
  for (int t = 0; t < kPad; ++t) b.row(t) = walk_pose(0, kPeriod);
  for (int t = 0; t < kWalkB; ++t) b.row(kPad + t) = walk_pose(t / kSlower, kPeriod);
  for (int t = 0; t < kPad; ++t) b.row(kPad + kWalkB + t) = walk_pose((kWalkB - 1) / kSlower, kPeriod);
  const SlopeDtwPath path = align_slope_dtw(a, b);
  check_path(path, a, b, 2, true);
  const auto [a_first, b_first] = path.steps.front();
  const auto [a_last, b_last] = path.steps.back();
  INFO("matched a " << a_first << ".." << a_last << ", b " << b_first << ".." << b_last << ", penalty "
                    << path.end_penalty);
  CHECK(std::abs(b_first - kPad) <= kPaddingSlack);
  CHECK(std::abs(b_last - (kPad + kWalkB - 1)) <= kPaddingSlack);
  CHECK(a_first <= kPaddingSlack);
  CHECK(a_last >= kWalkA - 1 - kPaddingSlack);
}

TEST_CASE("slope dtw: bad input and options throw InputError", "[slope_dtw]") {
  const Eigen::MatrixXd good = Eigen::MatrixXd::Ones(4, 2);
  SECTION("closed ends that no allowed path connects") {
    SlopeDtwOptions o;
    o.open_ends = false;
    // 19 frames of b against 2 steps of a: at most 2 x 2 = 4 with slope 2.
    CHECK_THROWS_AS(align_slope_dtw(Eigen::MatrixXd::Zero(3, 1), Eigen::MatrixXd::Zero(20, 1), o), InputError);
    CHECK_THROWS_WITH(align_slope_dtw(Eigen::MatrixXd::Zero(20, 1), Eigen::MatrixXd::Zero(3, 1), o),
                      Catch::Contains("open ends"));
    // The limit itself connects: 4 = 2 x (3 - 1).
    CHECK_NOTHROW(align_slope_dtw(Eigen::MatrixXd::Zero(3, 1), Eigen::MatrixXd::Zero(5, 1), o));
    CHECK_THROWS_AS(align_slope_dtw(Eigen::MatrixXd::Zero(3, 1), Eigen::MatrixXd::Zero(6, 1), o), InputError);
    // Open ends always find a path.
    CHECK_NOTHROW(align_slope_dtw(Eigen::MatrixXd::Zero(3, 1), Eigen::MatrixXd::Zero(20, 1)));
  }
  SECTION("a slope limit outside 2..4") {
    for (int slope : {1, 5, 0, -2}) {
      INFO("slope " << slope);
      SlopeDtwOptions o;
      o.max_slope = slope;
      CHECK_THROWS_AS(o.Validate(), InputError);
      CHECK_THROWS_AS(align_slope_dtw(good, good, o), InputError);
    }
  }
  SECTION("a non-finite penalty") {
    SlopeDtwOptions o;
    o.end_penalty = std::nan("");
    CHECK_THROWS_AS(align_slope_dtw(good, good, o), InputError);
    o.end_penalty = kInf;
    CHECK_THROWS_AS(align_slope_dtw(good, good, o), InputError);
  }
  SECTION("empty, mismatched or non-finite series") {
    CHECK_THROWS_AS(align_slope_dtw(Eigen::MatrixXd(0, 2), good), InputError);
    CHECK_THROWS_AS(align_slope_dtw(good, Eigen::MatrixXd(0, 2)), InputError);
    CHECK_THROWS_WITH(align_slope_dtw(good, Eigen::MatrixXd::Ones(4, 3)), Catch::Contains("different feature counts"));
    Eigen::MatrixXd with_nan = good;
    with_nan(1, 1) = std::nan("");
    CHECK_THROWS_AS(align_slope_dtw(with_nan, good), InputError);
    CHECK_THROWS_AS(align_slope_dtw(good, with_nan), InputError);
  }
}

TEST_CASE("slope dtw: cancellation and progress go through JobControl", "[slope_dtw]") {
  Random random(3);
  const Eigen::MatrixXd a = random_series(random, 30, 2), b = random_series(random, 20, 2);
  JobControl control;
  align_slope_dtw(a, b, {}, &control);
  CHECK(control.progress.load() == 1.0f);
  control.cancel = true;
  CHECK_THROWS_AS(align_slope_dtw(a, b, {}, &control), Cancelled);
  SlopeDtwOptions checkpointed;
  checkpointed.pointer_budget_bytes = 1;
  CHECK_THROWS_AS(align_slope_dtw(a, b, checkpointed, &control), Cancelled);
}
