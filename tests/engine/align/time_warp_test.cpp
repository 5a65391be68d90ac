#include "engine/align/time_warp.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <utility>
#include <vector>

#include "engine/align/slope_dtw.h"
#include "engine/base/error.h"
#include "tests/engine/synthetic_motion.h"

using namespace mostyle;
using mostyle::test::random_series;
using mostyle::test::Random;

namespace {

using Steps = std::vector<std::pair<int, int>>;

constexpr double kExact = 1e-9;       // frames: linear interpolation of integers, rounding only
constexpr double kChebyshev = 1e-9;   // the header's one frame per sample, up to rounding

Steps diagonal(int n) {
  Steps s;
  for (int i = 0; i < n; ++i) s.emplace_back(i, i);
  return s;
}

// From one sample to the next, neither take goes back, and the faster advances at most one frame.
void check_warp_steps(const TimeWarp& w) {
  REQUIRE(w.a.size() == w.b.size());
  for (int u = 1; u < w.samples(); ++u) {
    const double da = w.a[u] - w.a[u - 1], db = w.b[u] - w.b[u - 1];
    INFO("sample " << u << ": da " << da << ", db " << db);
    CHECK(da >= 0.0);
    CHECK(db >= 0.0);
    CHECK(std::max(da, db) <= 1.0 + kChebyshev);
  }
}

// A path of mixed allowed steps, (1, 1), (1, 2), (2, 1), (1, 3), from (2, 5).
Steps mixed_path() {
  Steps s = {{2, 5}};
  const std::pair<int, int> moves[] = {{1, 1}, {1, 2}, {1, 2}, {2, 1}, {1, 1}, {1, 3}, {1, 1}, {2, 1},
                                       {2, 1}, {1, 1}, {1, 2}, {1, 1}, {1, 1}, {2, 1}, {1, 1}};
  for (const auto& [di, dj] : moves) s.emplace_back(s.back().first + di, s.back().second + dj);
  return s;
}


}  // namespace

TEST_CASE("time warp: a diagonal path is the identity", "[time_warp]") {
  for (double smoothing : {0.0, kWarpSmoothingFrames, 10.0}) {
    INFO("smoothing " << smoothing);
    const TimeWarp w = smooth_warp(diagonal(12), smoothing);
    REQUIRE(w.samples() == 12);
    const Eigen::VectorXd frames = Eigen::VectorXd::LinSpaced(12, 0.0, 11.0);
    CHECK((w.a - frames).cwiseAbs().maxCoeff() < kExact);
    CHECK((w.b - frames).cwiseAbs().maxCoeff() < kExact);
  }
  // One vertex: one sample.
  const TimeWarp one = smooth_warp({{3, 7}});
  REQUIRE(one.samples() == 1);
  CHECK(one.a[0] == 3.0);
  CHECK(one.b[0] == 7.0);
}

TEST_CASE("time warp: a pure (1, 2) path keeps slope 2, one B frame per sample", "[time_warp]") {
  // (i, 2i), i = 0..9: B covers 18 frames, so 19 samples at b = 0, 1, .., 18 and a = b / 2.
  Steps path;
  for (int i = 0; i < 10; ++i) path.emplace_back(i, 2 * i);
  const TimeWarp w = smooth_warp(path);
  REQUIRE(w.samples() == 19);
  for (int u = 0; u < w.samples(); ++u) {
    INFO("sample " << u);
    CHECK(w.b[u] == Approx(u).margin(kExact));
    CHECK(w.a[u] == Approx(u / 2.0).margin(kExact));
  }
  for (int u = 1; u < w.samples(); ++u)
    CHECK((w.b[u] - w.b[u - 1]) / (w.a[u] - w.a[u - 1]) == Approx(2.0).epsilon(1e-9));
}

TEST_CASE("time warp: monotone, at most one frame a sample, ends kept", "[time_warp]") {
  SECTION("a hand-made path of mixed steps") {
    const Steps path = mixed_path();
    for (double smoothing : {0.0, 1.0, kWarpSmoothingFrames, 8.0}) {
      INFO("smoothing " << smoothing);
      const TimeWarp w = smooth_warp(path, smoothing);
      check_warp_steps(w);
      CHECK(w.a[0] == Approx(path.front().first).margin(kExact));
      CHECK(w.b[0] == Approx(path.front().second).margin(kExact));
      CHECK(w.a[w.samples() - 1] == Approx(path.back().first).margin(kExact));
      CHECK(w.b[w.samples() - 1] == Approx(path.back().second).margin(kExact));
      // The faster take advances about one frame a sample: no more samples than the path's
      // Chebyshev length + 1, no fewer than the longer matched range's.
      const int range_a = path.back().first - path.front().first, range_b = path.back().second - path.front().second;
      CHECK(w.samples() >= std::max(range_a, range_b) + 1);
    }
  }
  SECTION("slope DTW paths of random series") {
    Random random(42);
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::MatrixXd a = random_series(random, 40 + trial, 2), b = random_series(random, 70 - trial, 2);
      SlopeDtwOptions o;
      o.max_slope = 2 + trial % 3;
      const SlopeDtwPath path = align_slope_dtw(a, b, o);
      INFO("trial " << trial << ", " << path.steps.size() << " vertices");
      const TimeWarp w = smooth_warp(path.steps);
      check_warp_steps(w);
      CHECK(w.a[0] == Approx(path.steps.front().first).margin(kExact));
      CHECK(w.b[0] == Approx(path.steps.front().second).margin(kExact));
      CHECK(w.a[w.samples() - 1] == Approx(path.steps.back().first).margin(kExact));
      CHECK(w.b[w.samples() - 1] == Approx(path.steps.back().second).margin(kExact));
    }
  }
}

TEST_CASE("time warp: paper_warp is A's frames and warp_map", "[time_warp]") {
  DtwPath path;
  path.steps = {{0, 0}, {0, 1}, {1, 2}, {2, 2}, {2, 3}, {3, 4}};
  const TimeWarp w = paper_warp(path, 4);
  REQUIRE(w.samples() == 4);
  CHECK(w.a == Eigen::VectorXd::LinSpaced(4, 0.0, 3.0));
  CHECK(w.b == warp_map(path, 4));
  CHECK(w.b[0] == Approx(0.5));
  CHECK(w.b[2] == Approx(2.5));
  CHECK_THROWS_AS(paper_warp(path, 5), InputError);  // nothing matches frame 4
}

TEST_CASE("time warp: bad paths throw InputError", "[time_warp]") {
  CHECK_THROWS_AS(smooth_warp({}), InputError);
  CHECK_THROWS_AS(smooth_warp({{0, 0}, {1, 1}, {0, 2}}), InputError);  // A goes back
  CHECK_THROWS_AS(smooth_warp({{0, 0}, {1, 2}, {2, 1}}), InputError);  // B goes back
  CHECK_THROWS_WITH(smooth_warp({{0, 0}, {1, 1}, {1, 1}}), Catch::Contains("not monotone"));  // repeated vertex
  CHECK_THROWS_AS(smooth_warp(diagonal(4), -1.0), InputError);
  CHECK_THROWS_AS(smooth_warp(diagonal(4), std::nan("")), InputError);
}

TEST_CASE("joined warps: one after another, the shared sample once; warps that do not meet are refused") {
  // A hold of A at its frame 0 over B's first 3 frames, then both one frame a sample.
  TimeWarp hold, run;
  hold.a = Eigen::VectorXd::Zero(4);
  hold.b = Eigen::VectorXd::LinSpaced(4, 0.0, 3.0);
  run.a = Eigen::VectorXd::LinSpaced(3, 0.0, 2.0);
  run.b = Eigen::VectorXd::LinSpaced(3, 3.0, 5.0);
  const TimeWarp joined = joined_warps({hold, run});
  Eigen::VectorXd a(6), b(6);
  a << 0, 0, 0, 0, 1, 2;
  b << 0, 1, 2, 3, 4, 5;
  CHECK(joined.a == a);
  CHECK(joined.b == b);
  CHECK(joined_warps({run}).a == run.a);
  CHECK_THROWS_AS(joined_warps({run, hold}), InputError);  // run ends at (2, 5), hold starts at (0, 0)
  CHECK_THROWS_AS(joined_warps({}), InputError);
  CHECK_THROWS_AS(joined_warps({hold, TimeWarp()}), InputError);
}
