#include "engine/align/dtw.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>

#include "engine/base/error.h"
#include "engine/base/job_control.h"

using namespace mostyle;

namespace {

// Costs are sums of up to ~80 rounded distances computed in different orders.
constexpr double kCostTolerance = 1e-9;  // relative
constexpr double kWarpTolerance = 1e-12;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The band of dtw.h written independently of dtw.cpp's row ranges: |j - i(m-1)/(n-1)| <=
// band, cross-multiplied; the degenerate diagonal of a one-frame a covers its whole row.
bool in_band(int i, int j, int n, int m, int band) {
  if (band < 0 || n == 1) return true;
  return std::llabs(std::int64_t{j} * (n - 1) - std::int64_t{i} * (m - 1)) <=
         std::int64_t{band} * (n - 1);
}

double distance(const Eigen::MatrixXd& a, int i, const Eigen::MatrixXd& b, int j) {
  return (a.row(i) - b.row(j)).norm();
}

// Textbook DTW with the whole n x m matrix: +inf outside the band or when unreachable.
double brute_force_cost(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, int band = -1) {
  const int n = static_cast<int>(a.rows()), m = static_cast<int>(b.rows());
  Eigen::MatrixXd d = Eigen::MatrixXd::Constant(n, m, kInf);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      if (!in_band(i, j, n, m, band)) continue;
      double best = i == 0 && j == 0 ? 0.0 : kInf;
      if (i > 0) best = std::min(best, d(i - 1, j));
      if (j > 0) best = std::min(best, d(i, j - 1));
      if (i > 0 && j > 0) best = std::min(best, d(i - 1, j - 1));
      d(i, j) = distance(a, i, b, j) + best;
    }
  }
  return d(n - 1, m - 1);
}

// A path is valid when it runs from (0,0) to (n-1,m-1) in legal steps inside the band; it is
// optimal when its summed local cost is the brute-force optimum.
void check_optimal_path(const DtwPath& path, const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                        int band, double optimum) {
  const int n = static_cast<int>(a.rows()), m = static_cast<int>(b.rows());
  REQUIRE(!path.steps.empty());
  CHECK(path.steps.front() == std::make_pair(0, 0));
  CHECK(path.steps.back() == std::make_pair(n - 1, m - 1));
  double sum = 0.0;
  for (std::size_t k = 0; k < path.steps.size(); ++k) {
    const auto [i, j] = path.steps[k];
    REQUIRE(in_band(i, j, n, m, band));
    if (k > 0) {
      const int di = i - path.steps[k - 1].first, dj = j - path.steps[k - 1].second;
      INFO("step " << k << " from (" << path.steps[k - 1].first << ", "
                   << path.steps[k - 1].second << ") to (" << i << ", " << j << ")");
      REQUIRE((di == 0 || di == 1));
      REQUIRE((dj == 0 || dj == 1));
      REQUIRE(di + dj > 0);
    }
    sum += distance(a, i, b, j);
  }
  CHECK(sum == Approx(optimum).epsilon(kCostTolerance));
  CHECK(path.cost == Approx(optimum).epsilon(kCostTolerance));
}

Eigen::MatrixXd column(std::initializer_list<double> values) {
  Eigen::MatrixXd x(static_cast<Eigen::Index>(values.size()), 1);
  Eigen::Index i = 0;
  for (double v : values) x(i++, 0) = v;
  return x;
}

// Random-walk series (smooth like motion) or small integers (many exact ties), by the coin.
Eigen::MatrixXd random_series(std::mt19937& rng, int frames, int features, bool integers) {
  Eigen::MatrixXd x(frames, features);
  std::normal_distribution<double> step(0.0, 1.0);
  std::uniform_int_distribution<int> small(0, 2);
  for (int k = 0; k < features; ++k) {
    double v = 0.0;
    for (int i = 0; i < frames; ++i) {
      v += step(rng);
      x(i, k) = integers ? small(rng) : v;
    }
  }
  return x;
}

}  // namespace

TEST_CASE("dtw: hand-worked 4 x 3 case", "[dtw]") {
  // a = 0 2 3 5, b = 0 3 5, c(i,j) = |a_i - b_j|. D by hand (rows i, columns j):
  //            b=0   b=3   b=5
  //   a=0:      0     3     8
  //   a=2:      2     1     4      D(1,1) = 1 + min(3, 2, 0)
  //   a=3:      5     1     3      D(2,1) = 0 + min(1, 5, 2)
  //   a=5:     10     3     1      D(3,2) = 0 + min(3, 3, 1)
  // The only path of cost 1 is (0,0) (1,1) (2,1) (3,2): every path visits row 1, whose
  // cheapest cell costs 1, and the three cells of cost 0 are (0,0), (2,1), (3,2).
  const Eigen::MatrixXd a = column({0, 2, 3, 5}), b = column({0, 3, 5});
  const std::vector<std::pair<int, int>> expected = {{0, 0}, {1, 1}, {2, 1}, {3, 2}};
  DtwOptions pointers, divide;
  divide.pointer_budget_bytes = 0;
  for (const DtwOptions& o : {pointers, divide}) {
    const DtwPath path = align_dtw(a, b, o);
    CHECK(path.cost == 1.0);
    CHECK(path.steps == expected);
  }
  // Swapping the series transposes the path and keeps the cost.
  const DtwPath swapped = align_dtw(b, a);
  CHECK(swapped.cost == 1.0);
  CHECK(swapped.steps == std::vector<std::pair<int, int>>{{0, 0}, {1, 1}, {1, 2}, {2, 3}});
}

TEST_CASE("dtw: local cost is the Euclidean distance of rows", "[dtw]") {
  Eigen::MatrixXd a(1, 2), b(1, 2);
  a << 0, 0;
  b << 3, 4;
  CHECK(align_dtw(a, b).cost == 5.0);  // not 7 (L1) nor 25 (squared)
  Eigen::MatrixXd a4(2, 4), b4(1, 4);  // more features than the unrolled cases
  a4 << 1, 1, 1, 1, 0, 0, 0, 0;
  b4 << 0, 0, 0, 0;
  CHECK(align_dtw(a4, b4).cost == 2.0);
}

TEST_CASE("dtw: one frame against many matches it to every frame", "[dtw]") {
  const Eigen::MatrixXd one = column({1}), many = column({0, 1, 3});
  const DtwPath path = align_dtw(one, many);
  CHECK(path.steps == std::vector<std::pair<int, int>>{{0, 0}, {0, 1}, {0, 2}});
  CHECK(path.cost == 3.0);
  const DtwPath transposed = align_dtw(many, one, DtwOptions{0});  // a band of 0 suffices
  CHECK(transposed.steps == std::vector<std::pair<int, int>>{{0, 0}, {1, 0}, {2, 0}});
}

TEST_CASE("dtw: equals brute force on random series", "[dtw]") {
  std::mt19937 rng(20240611);
  std::uniform_int_distribution<int> frames(1, 40), features(1, 3), band_pick(-1, 8);
  DtwOptions divide, mixed;
  divide.pointer_budget_bytes = 0;  // divide and conquer down to single rows and columns
  mixed.pointer_budget_bytes = 64;  // divide and conquer until a sub-problem is small
  int banded = 0, rejected = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = frames(rng), m = frames(rng), d = features(rng);
    const bool integers = trial % 3 == 0;
    const Eigen::MatrixXd a = random_series(rng, n, d, integers);
    const Eigen::MatrixXd b = random_series(rng, m, d, integers);
    const int band = trial % 2 == 0 ? -1 : band_pick(rng);
    INFO("trial " << trial << ": " << n << " x " << m << ", d " << d << ", band " << band);
    const double optimum = brute_force_cost(a, b, band);
    for (DtwOptions o : {DtwOptions{}, divide, mixed}) {
      o.band = band;
      INFO("pointer budget " << o.pointer_budget_bytes);
      if (optimum == kInf) {  // no path inside the band: it must refuse
        CHECK_THROWS_AS(align_dtw(a, b, o), InputError);
        continue;
      }
      check_optimal_path(align_dtw(a, b, o), a, b, band, optimum);
    }
    banded += band >= 0 && optimum < kInf;
    rejected += optimum == kInf;
  }
  CHECK(banded > 50);    // the band cases are really exercised ...
  CHECK(rejected > 10);  // ... and so is the refusal of a band too narrow
}

TEST_CASE("dtw: every small size and band agrees with brute force", "[dtw]") {
  // Exhaustive over shapes, so every way a band can fail to connect (an empty row, a gap of one
  // or more columns between rows) meets the brute force's verdict.
  std::mt19937 rng(99);
  DtwOptions divide;
  divide.pointer_budget_bytes = 0;
  for (int n = 1; n <= 12; ++n) {
    for (int m = 1; m <= 12; ++m) {
      const Eigen::MatrixXd a = random_series(rng, n, 2, false);
      const Eigen::MatrixXd b = random_series(rng, m, 2, false);
      for (int band = -1; band <= 6; ++band) {
        INFO(n << " x " << m << ", band " << band);
        const double optimum = brute_force_cost(a, b, band);
        for (DtwOptions o : {DtwOptions{}, divide}) {
          o.band = band;
          if (optimum == kInf) {
            CHECK_THROWS_WITH(align_dtw(a, b, o), Catch::Contains("too narrow"));
          } else {
            check_optimal_path(align_dtw(a, b, o), a, b, band, optimum);
                }
        }
      }
    }
  }
}

TEST_CASE("dtw: divide and conquer on a longer banded pair equals brute force", "[dtw]") {
  std::mt19937 rng(7);
  const Eigen::MatrixXd a = random_series(rng, 300, 3, false);
  const Eigen::MatrixXd b = random_series(rng, 220, 3, false);
  for (int band : {-1, 12}) {
    const double optimum = brute_force_cost(a, b, band);
    REQUIRE(optimum < kInf);
    for (std::size_t budget : {std::size_t{0}, std::size_t{3000}, std::size_t{1} << 20}) {
      INFO("band " << band << ", budget " << budget);
      DtwOptions o;
      o.band = band;
      o.pointer_budget_bytes = budget;
      check_optimal_path(align_dtw(a, b, o), a, b, band, optimum);
    }
  }
}

TEST_CASE("dtw: a band narrows the search around the scaled diagonal", "[dtw]") {
  // Two frames against ten: row 0 may use j in [0, band], row 1 j in [9 - band, 9]; they
  // connect when 9 - band <= band + 1, so from band 4 on.
  const Eigen::MatrixXd a = column({0, 9});
  const Eigen::MatrixXd b = column({0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  CHECK_NOTHROW(align_dtw(a, b, DtwOptions{4}));
  try {
    align_dtw(a, b, DtwOptions{3});
    FAIL("a band of 3 was accepted");
  } catch (const InputError& e) {
    const std::string message = e.what();
    CHECK(message.find("too narrow") != std::string::npos);
    CHECK(message.find("at least 4") != std::string::npos);
  }
  // Two frames against nine: rows [0, band] and [8 - band, 8] leave a gap of two columns at
  // band 3, and need 8 - band <= band + 1, so a band of 4.
  const Eigen::MatrixXd b9 = b.topRows(9);
  CHECK_THROWS_WITH(align_dtw(a, b9, DtwOptions{3}), Catch::Contains("at least 4"));
  CHECK_NOTHROW(align_dtw(a, b9, DtwOptions{4}));
  // Unconstrained, frame 0 of a takes b's 0..4 and frame 1 the rest; a band of 4 allows it.
  const DtwPath free = align_dtw(a, b);
  CHECK(align_dtw(a, b, DtwOptions{4}).cost == free.cost);
  CHECK(free.cost == 0 + 1 + 2 + 3 + 4 + 4 + 3 + 2 + 1 + 0);
}

TEST_CASE("dtw: bad input throws InputError", "[dtw]") {
  const Eigen::MatrixXd good = Eigen::MatrixXd::Ones(4, 3);
  Eigen::MatrixXd with_nan = good, with_inf = good;
  with_nan(2, 1) = std::nan("");
  with_inf(3, 0) = kInf;
  const auto throws = [](const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const DtwOptions& o,
                          const char* words) {
    CHECK_THROWS_WITH(align_dtw(a, b, o), Catch::Contains(words));
    CHECK_THROWS_AS(align_dtw(a, b, o), InputError);
  };
  throws(Eigen::MatrixXd(0, 3), good, {}, "a is empty");
  throws(good, Eigen::MatrixXd(0, 3), {}, "b is empty");
  throws(Eigen::MatrixXd(4, 0), Eigen::MatrixXd(4, 0), {}, "empty");
  throws(good, Eigen::MatrixXd::Ones(4, 2), {}, "different feature counts");
  throws(with_nan, good, {}, "non-finite value (nan) at frame 2, feature 1");
  throws(good, with_inf, {}, "b has a non-finite value");
  throws(good, good, DtwOptions{-2}, "band must be -1");
  throws(Eigen::MatrixXd::Ones(2, 3), Eigen::MatrixXd::Ones(10, 3), DtwOptions{0}, "too narrow");
  // Finite values whose squared differences overflow.
  throws(Eigen::MatrixXd::Constant(3, 1, 1e200), Eigen::MatrixXd::Constant(3, 1, -1e200), {},
         "overflowed");
  DtwOptions divide;
  divide.pointer_budget_bytes = 0;
  throws(Eigen::MatrixXd::Constant(3, 1, 1e200), Eigen::MatrixXd::Constant(5, 1, -1e200), divide,
         "overflowed");
}

TEST_CASE("dtw: cancellation and progress go through JobControl", "[dtw]") {
  std::mt19937 rng(3);
  const Eigen::MatrixXd a = random_series(rng, 30, 2, false);
  const Eigen::MatrixXd b = random_series(rng, 20, 2, false);
  JobControl control;
  align_dtw(a, b, {}, &control);
  CHECK(control.progress.load() == 1.0f);
  control.cancel = true;
  CHECK_THROWS_AS(align_dtw(a, b, {}, &control), Cancelled);
  DtwOptions divide;
  divide.pointer_budget_bytes = 0;
  CHECK_THROWS_AS(align_dtw(a, b, divide, &control), Cancelled);
}

TEST_CASE("dtw: warp_map on a known path", "[dtw]") {
  DtwPath path;
  // Frame 0 of a matches b's 0 and 1, frame 1 matches 2, frame 2 matches 2 and 3... in steps:
  path.steps = {{0, 0}, {0, 1}, {1, 2}, {2, 2}, {2, 3}, {3, 4}};
  const Eigen::VectorXd where = warp_map(path, 4);
  REQUIRE(where.size() == 4);
  CHECK(where[0] == Approx(0.5).margin(kWarpTolerance));
  CHECK(where[1] == Approx(2.0).margin(kWarpTolerance));
  CHECK(where[2] == Approx(2.5).margin(kWarpTolerance));
  CHECK(where[3] == Approx(4.0).margin(kWarpTolerance));

  // A real alignment puts b on a's timeline: b is a slowed down (each frame twice), so a's
  // frame i matches b's 2i and 2i + 1.
  const Eigen::MatrixXd a = column({0, 1, 2, 3});
  const Eigen::MatrixXd slow = column({0, 0, 1, 1, 2, 2, 3, 3});
  const DtwPath aligned = align_dtw(a, slow);
  CHECK(aligned.cost == 0.0);
  const Eigen::VectorXd onto = warp_map(aligned, 4);
  for (int i = 0; i < 4; ++i) CHECK(onto[i] == Approx(2 * i + 0.5).margin(kWarpTolerance));
}

TEST_CASE("dtw: warp_map rejects paths that do not fit", "[dtw]") {
  DtwPath path;
  path.steps = {{0, 0}, {1, 1}, {3, 2}};
  CHECK_THROWS_WITH(warp_map(path, 4), Catch::Contains("nothing to frame 2"));
  CHECK_THROWS_AS(warp_map(path, 0), InputError);
  CHECK_THROWS_WITH(warp_map(path, 3), Catch::Contains("(3, 2) lies outside"));
  DtwPath negative;
  negative.steps = {{0, -1}};
  CHECK_THROWS_AS(warp_map(negative, 1), InputError);
  CHECK_THROWS_AS(warp_map(DtwPath{}, 1), InputError);
}
