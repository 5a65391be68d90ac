#include "engine/trajectory/mixed_clock.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <utility>
#include <vector>

#include "engine/align/common_timeline.h"
#include "engine/align/slope_dtw.h"
#include "engine/base/error.h"
#include "tests/engine/align/made_warps.h"

using namespace mostyle;
using test::warp_of;

namespace {

constexpr double kExact = 1e-9;  // frames: piecewise-linear arithmetic, rounding only

// v linearly interpolated at fractional sample u, written here independently of the engine.
double at(const Eigen::VectorXd& v, double u) {
  const Eigen::Index i = std::min<Eigen::Index>(static_cast<Eigen::Index>(std::floor(u)), v.size() - 2);
  const double f = u - static_cast<double>(i);
  return (1 - f) * v[i] + f * v[i + 1];
}

// A timeline of two takes whose samples are the warp's own (the clock read on given samples;
// common_timeline's own sampling is its test's).
CommonTimeline samples_of(const TimeWarp& w) {
  CommonTimeline t;
  t.frames = {w.a, w.b};
  t.first = {0, 0};
  t.last = {w.samples() - 1, w.samples() - 1};
  return t;
}

// The output frames of takes A and B (one warp) mixed with weights (1 - weight, weight).
Eigen::VectorXd timeline(const TimeWarp& w, double weight) {
  const CommonTimeline t = samples_of(w);
  Eigen::VectorXd u;
  mixed_timeline(t, {1.0 - weight, weight}, {0, t.samples() - 1}, u);
  return u;
}

// The mixed clock at every sample, written here independently of the engine: each step the
// weighted advance of A and B, never less than the slower take with a weight advances.
Eigen::VectorXd clock_of(const TimeWarp& w, double weight) {
  Eigen::VectorXd clock(w.samples());
  clock[0] = 0.0;
  for (int k = 1; k < w.samples(); ++k) {
    const double da = w.a[k] - w.a[k - 1], db = w.b[k] - w.b[k - 1];
    const double slowest = weight == 0.0 ? da : weight == 1.0 ? db : std::min(da, db);
    clock[k] = clock[k - 1] + std::max(0.0, std::max((1.0 - weight) * da + weight * db, slowest));
  }
  return clock;
}

bool non_decreasing(const Eigen::VectorXd& v) {
  for (Eigen::Index k = 1; k < v.size(); ++k)
    if (v[k] < v[k - 1]) return false;
  return true;
}

// A realistic warp: a walk against a version of it 1.4 times slower in its middle part.
TimeWarp walk_warp() {
  Eigen::MatrixXd a(80, 2), b(100, 2);
  auto pose = [](double t) { return Eigen::RowVector2d(std::sin(2 * M_PI * t / 25), std::cos(2 * M_PI * t / 25)); };
  for (int t = 0; t < 80; ++t) a.row(t) = pose(t);
  for (int t = 0; t < 100; ++t) {
    const double slow = t < 30 ? t : t < 86 ? 30 + (t - 30) / 1.4 : 70 + (t - 86);
    b.row(t) = pose(slow);
  }
  return smooth_warp(align_slope_dtw(a, b).steps);
}

}  // namespace

TEST_CASE("timing: the hand-worked warp a = 0 1 2 3, b = 0 2 4 6", "[timing]") {
  // B advances two frames a sample (steeper than smooth_warp makes; the timeline must not care).
  const TimeWarp w = warp_of({0, 1, 2, 3}, {0, 2, 4, 6});
  SECTION("w = 1: B's clock, 7 frames at every half sample") {
    const Eigen::VectorXd u = timeline(w, 1.0);
    REQUIRE(u.size() == 7);
    for (int k = 0; k < 7; ++k) CHECK(u[k] == Approx(0.5 * k).margin(kExact));
    CHECK((clock_of(w, 1.0) - Eigen::Vector4d(0, 2, 4, 6)).cwiseAbs().maxCoeff() < kExact);
  }
  SECTION("w = 0: A's clock, one frame a sample") {
    const Eigen::VectorXd u = timeline(w, 0.0);
    REQUIRE(u.size() == 4);
    for (int k = 0; k < 4; ++k) CHECK(u[k] == Approx(k).margin(kExact));
  }
  SECTION("w = 0.5: the clock advances 1.5 a sample, 5 frames") {
    // T = 0, 1.5, 3, 4.5: frame k at u = k / 1.5.
    const Eigen::VectorXd u = timeline(w, 0.5);
    REQUIRE(u.size() == 5);
    for (int k = 0; k < 5; ++k) CHECK(u[k] == Approx(k / 1.5).margin(kExact));
  }
}

TEST_CASE("timing: where the blended clock would run backwards, it advances as the slower take", "[timing]") {
  // w = 2 (exaggerating B): steps -1 + 2 x 2 = 3, then -1 + 2 x 0.2 < 0 twice, where B, the
  // slower, advances by 0.2: T = 0 3 3.2 3.4.
  const TimeWarp w = warp_of({0, 1, 2, 3}, {0, 2, 2.2, 2.4});
  CHECK((clock_of(w, 2.0) - Eigen::Vector4d(0, 3, 3.2, 3.4)).cwiseAbs().maxCoeff() < kExact);
  const Eigen::VectorXd u = timeline(w, 2.0);
  REQUIRE(u.size() == 4);
  for (int k = 0; k < 4; ++k) CHECK(u[k] == Approx(k / 3.0).margin(kExact));
}

TEST_CASE("timing: w = 0 plays A's frames, w = 1 B's, 0.5 in between", "[timing]") {
  // The warp as its common timeline samples it (A's whole frames among the samples): the output
  // frames are read on those samples.
  const TimeWarp walk = walk_warp();
  const CommonTimeline on = common_timeline({&walk});
  TimeWarp w;
  w.a = on.frames[0];
  w.b = on.frames[1];
  REQUIRE(w.samples() > 1);
  const double a0 = w.a[0], b0 = w.b[0];
  const double range_a = w.a[w.samples() - 1] - a0, range_b = w.b[w.samples() - 1] - b0;
  INFO("A " << a0 << " + " << range_a << ", B " << b0 << " + " << range_b << ", " << w.samples() << " samples");
  REQUIRE(range_b > range_a + 5);  // the warp really has two timings

  const Eigen::VectorXd u0 = timeline(w, 0.0);
  CHECK(u0.size() == static_cast<Eigen::Index>(std::floor(range_a + 1e-9)) + 1);
  for (Eigen::Index k = 0; k < u0.size(); ++k) {
    INFO("output frame " << k << " at sample " << u0[k]);
    CHECK(at(w.a, u0[k]) - a0 == Approx(k).margin(kExact));  // on A's frames, one per output frame
    if (a0 == 0.0) CHECK(u0[k] == Approx(std::round(u0[k])).margin(kExact));  // and on samples: A's own poses
  }
  CHECK(w.a[0] == 0.0);

  const Eigen::VectorXd u1 = timeline(w, 1.0);
  CHECK(u1.size() == static_cast<Eigen::Index>(std::floor(range_b + 1e-9)) + 1);
  for (Eigen::Index k = 0; k < u1.size(); ++k) CHECK(at(w.b, u1[k]) - b0 == Approx(k).margin(kExact));

  const Eigen::VectorXd half = timeline(w, 0.5);
  CHECK(half.size() >= u0.size());
  CHECK(half.size() <= u1.size());
  CHECK(half.size() == static_cast<Eigen::Index>(std::floor(0.5 * (range_a + range_b) + 1e-9)) + 1);

  for (double weight : {0.0, 0.25, 0.5, 0.75, 1.0, 1.3, -0.3}) {
    INFO("w " << weight);
    const Eigen::VectorXd u = timeline(w, weight);
    CHECK(non_decreasing(u));
    CHECK(u[0] == 0.0);
    CHECK(u.minCoeff() >= 0.0);
    CHECK(u.maxCoeff() <= w.samples() - 1.0);
    // The clock at each output frame is the frame's number.
    const Eigen::VectorXd clock = clock_of(w, weight);
    CHECK(non_decreasing(clock));
    for (Eigen::Index k = 0; k < u.size(); ++k) CHECK(at(clock, u[k]) == Approx(k).margin(1e-7));
  }
}

TEST_CASE("timing: no allocation when u has the right size", "[timing]") {
  const TimeWarp w = warp_of({0, 1, 2, 3}, {0, 2, 4, 6});
  const CommonTimeline t = samples_of(w);
  Eigen::VectorXd u(7);
  const double* data = u.data();
  mixed_timeline(t, {0.0, 1.0}, {0, 3}, u);
  CHECK(u.data() == data);
}

TEST_CASE("timing: a one-sample warp gives one frame, bad input throws InputError", "[timing]") {
  const TimeWarp one = warp_of({4}, {9});
  const Eigen::VectorXd u = timeline(one, 0.5);
  REQUIRE(u.size() == 1);
  CHECK(u[0] == 0.0);
  const CommonTimeline t = common_timeline({&one});
  Eigen::VectorXd out;
  const TimeWarp empty;
  CHECK_THROWS_AS(common_timeline({&empty}), InputError);
  CHECK_THROWS_AS(mixed_timeline(t, {0.5, std::nan("")}, {0, 0}, out), InputError);
  CHECK_THROWS_AS(mixed_timeline(t, {0.5, INFINITY}, {0, 0}, out), InputError);
}

TEST_CASE("timing: three takes' clock advances by the weighted frames", "[timing]") {
  // Reference 0..4, take 1 twice as fast, take 2 as fast as the reference: weights (0.5, 0.5, 0)
  // give 1.5 frames per reference frame, 6 frames in all (7 output frames).
  CommonTimeline t;
  t.frames = {Eigen::VectorXd::LinSpaced(9, 0, 4), Eigen::VectorXd::LinSpaced(9, 0, 8),
              Eigen::VectorXd::LinSpaced(9, 10, 14)};
  Eigen::VectorXd u;
  mixed_timeline(t, {0.5, 0.5, 0.0}, {0, 8}, u);
  REQUIRE(u.size() == 7);
  for (Eigen::Index f = 0; f < u.size(); ++f) CHECK(u[f] == Approx(f * 8.0 / 6.0).margin(kExact));
  CHECK_THROWS_AS(mixed_timeline(t, {0.5, 0.5}, {0, 8}, u), InputError);
  CHECK_THROWS_AS(mixed_timeline(t, {0.5, 0.5, 0.0}, {2, 9}, u), InputError);
  mixed_timeline(t, {0.0, 1.0, 0.0}, {2, 6}, u);  // take 1 from its frame 2 to 6: 5 frames
  REQUIRE(u.size() == 5);
  CHECK(u[0] == Approx(2.0));
  CHECK(u[4] == Approx(6.0));
  CHECK_THROWS_AS(mixed_timeline(t, {0.5, NAN, 0.5}, {0, 8}, u), InputError);
}

TEST_CASE("timing: a whole loop's clock lands on its last sample, stretched evenly", "[timing]") {
  // Frames every 0.9 samples from 0 reach 9 of 10 samples (0..9) at 10 frames (8.1) and would
  // reach sample 9 at 10 frames: 11 frames, the last on 9.
  Eigen::VectorXd u(10);
  for (int k = 0; k < 10; ++k) u[k] = 0.9 * k;
  land_on_last(u, 9.0, 10.0);
  REQUIRE(u.size() == 11);
  for (int k = 0; k < 11; ++k) CHECK(u[k] == Approx(0.9 * k));
  // Frames every 0.8 reach 8.8 at 12 frames; sample 9 at 11.25: rounded to 11 steps of 9/11.
  u.resize(12);
  for (int k = 0; k < 12; ++k) u[k] = 0.8 * k;
  land_on_last(u, 9.0, 11.25);
  REQUIRE(u.size() == 12);
  for (int k = 0; k < 12; ++k) CHECK(u[k] == Approx(9.0 * k / 11.0));
  // Already on it: unchanged.
  u.resize(4);
  u << 0.0, 1.0, 2.0, 3.0;
  land_on_last(u, 3.0, 3.0);
  REQUIRE(u.size() == 4);
  CHECK(u[3] == 3.0);
}

TEST_CASE("timing: a loop's clock lands by the clock's end, not by its last step carried on", "[timing]") {
  // Frames on samples 0, 2, 4, 5 (the samples twice as dense, then not), and the clock reaching
  // sample 7 at 3.5 frames (denser again after 5): 3.5 rounds to 4 steps of 3.5 / 4 frames, read
  // on (0, 0) (1, 2) (2, 4) (3, 5) (3.5, 7). Its last step carried on (one sample a frame) would
  // have reached sample 7 at frame 5: a frame too many.
  Eigen::VectorXd u(4);
  u << 0.0, 2.0, 4.0, 5.0;
  land_on_last(u, 7.0, 3.5);
  REQUIRE(u.size() == 5);
  const double expected[5] = {0.0, 1.75, 3.5, 4.625, 7.0};
  for (int k = 0; k < 5; ++k) CHECK(u[k] == Approx(expected[k]));
}

TEST_CASE("timing: the clock's end is given with the frames", "[timing]") {
  // Frames every 0.9 samples over samples 0..9: T(9) = 10, still advancing at sample 9.
  CommonTimeline t;
  t.frames = {Eigen::VectorXd::LinSpaced(10, 0, 9), Eigen::VectorXd::LinSpaced(10, 0, 9 / 0.9)};
  Eigen::VectorXd u;
  ClockEnd end;
  end.clock = -1.0;
  mixed_timeline(t, {0.0, 1.0}, {0, 9}, u, &end);
  CHECK(end.clock == Approx(10.0));
  CHECK(end.sample == 9);
  CHECK(u.size() == 11);
  end = ClockEnd{-1.0, -1};
  mixed_timeline(t, WeightKeys{{0.0, {0.0, 1.0}}}, 30.0, {0, 9}, u, nullptr, &end);
  CHECK(end.clock == Approx(10.0));
  CHECK(end.sample == 9);
}

TEST_CASE("timing: on A's clock its last frame is where A reaches it, not the end of B's rest held against it", "[timing]") {
  // A plays frames 0..6 over samples 0..6, then holds frame 6 while B plays 3 frames of rest
  // (samples 7..9). On A's clock the clock ends at sample 6: a loop of A lands there, so its last
  // frame shows B where A's last frame meets it, not B three frames on.
  const TimeWarp rest_last = warp_of({0, 1, 2, 3, 4, 5, 6, 6, 6, 6}, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  const CommonTimeline t = common_timeline({&rest_last});
  REQUIRE(t.samples() == 10);
  Eigen::VectorXd u;
  ClockEnd end;
  mixed_timeline(t, {1.0, 0.0}, {0, 9}, u, &end);
  CHECK(end.clock == Approx(6.0));
  CHECK(end.sample == 6);
  REQUIRE(u.size() == 7);
  CHECK(u[6] == Approx(6.0));
  land_on_last(u, end.sample, end.clock);
  REQUIRE(u.size() == 7);
  for (int k = 0; k < 7; ++k) CHECK(u[k] == Approx(double(k)));
  // On B's clock the rest plays: the clock runs to the last sample.
  mixed_timeline(t, {0.0, 1.0}, {0, 9}, u, &end);
  CHECK(end.clock == Approx(9.0));
  CHECK(end.sample == 9);
}

TEST_CASE("timing: a hold of the reference takes B's time at B's weight, none on A's clock, where the output starts", "[timing]") {
  // B plays 3 frames of rest while A holds its first frame, then both run 6 frames together.
  const TimeWarp rest_first = warp_of({0, 0, 0, 0, 1, 2, 3, 4, 5, 6}, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  const CommonTimeline t = common_timeline({&rest_first});
  REQUIRE(t.samples() == 10);
  for (const auto& [weight, frames] : {std::pair{0.0, 7}, std::pair{1.0, 10}, std::pair{0.5, 8}}) {
    Eigen::VectorXd u;
    mixed_timeline(t, {1.0 - weight, weight}, {0, t.samples() - 1}, u);
    INFO("weight " << weight);
    REQUIRE(u.size() == frames);
    CHECK(non_decreasing(u));
    // A's frame at each output frame: held at 0 while the hold plays, then one a frame.
    const double a_last = at(t.frames[0], u[u.size() - 1]), b_first = at(t.frames[1], u[0]);
    CHECK(a_last == Approx(weight == 0.5 ? 5.5 : 6.0).margin(kExact));  // 0.5: the clock ends at 7.5
    // On A's clock the hold takes no time, and the output starts where it ends (B's frame 3),
    // so that its second frame does not leap over B's rest.
    CHECK(b_first == Approx(weight == 0.0 ? 3.0 : 0.0).margin(kExact));
    if (weight == 0.0) CHECK(at(t.frames[1], u[1]) == Approx(4.0).margin(kExact));
  }
  Eigen::VectorXd u;
  mixed_timeline(t, {1.0, 0.0}, {0, t.samples() - 1}, u);
  for (Eigen::Index k = 0; k < u.size(); ++k) CHECK(at(t.frames[0], u[k]) == Approx(double(k)).margin(kExact));
}

TEST_CASE("cycle slots: one-hot weights play that take's own slots, weights between two a count between", "[clock]") {
  // Slot shares of a take with 5 own cycles of 7 slots (its own first five) and one with all 7.
  auto played = [](double w) {
    SlotCount count;
    std::vector<int> out;
    for (int s = 0; s < 7; ++s)
      if (count.play((1.0 - w) * (s < 5 ? 1.0 : 0.0) + w * 1.0)) out.push_back(s);
    return out;
  };
  CHECK(played(0.0) == std::vector<int>{0, 1, 2, 3, 4});
  CHECK(played(1.0) == std::vector<int>{0, 1, 2, 3, 4, 5, 6});
  CHECK(played(0.5).size() == 6);  // round(0.5 x 5 + 0.5 x 7)
  CHECK(played(0.25).size() == 6);  // round(0.75 x 5 + 0.25 x 7) = round(5.5), half up
  CHECK(played(0.2).size() == 5);   // round(5.4)
  // Shares out of [0, 1] (an exaggeration) are held to it.
  SlotCount wide;
  CHECK(wide.play(1.5));
  CHECK_FALSE(wide.play(-0.5));
}
