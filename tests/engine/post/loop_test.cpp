#include "engine/post/loop.h"

#include <catch2/catch.hpp>

#include <cmath>

#include "engine/base/error.h"

using namespace mostyle;

namespace {

constexpr int kPeriod = 24;       // frames per gait cycle
constexpr int kFrames = 200;      // a little over 8 cycles
constexpr int kOffset = 5;        // the first left-foot strike's frame (the take starts mid-cycle)
constexpr int kJoints = 4;
constexpr double kSpeed = 3.0;    // ground units per frame along +X
constexpr double kHeading = 0.3;  // radians, constant
constexpr double kDrift = 0.002;  // pose change per frame on top of the cycle, so that no two
                                  // cycles end exactly where they start
constexpr double kExact = 1e-9;

struct Walk {
  Eigen::MatrixXd contacts, local, ground;
  Eigen::VectorXd heading;
};

// A periodic walk: contacts from a square wave (left foot planted in the first half of each
// cycle, the right in the second), each joint's local pose sin / cos of the phase (plus a slow
// drift up), the ground moving at constant speed and the heading constant.
Walk periodic_walk(double drift = kDrift) {
  Walk w;
  w.contacts.resize(kFrames, 2);
  w.local.resize(kFrames, 3 * kJoints);
  w.ground.resize(kFrames, 2);
  w.heading = Eigen::VectorXd::Constant(kFrames, kHeading);
  for (int t = 0; t < kFrames; ++t) {
    const int in_cycle = ((t - kOffset) % kPeriod + kPeriod) % kPeriod;
    const double phase = 2.0 * M_PI * in_cycle / kPeriod;
    w.contacts(t, 0) = in_cycle < kPeriod / 2 ? 1.0 : 0.0;
    w.contacts(t, 1) = in_cycle < kPeriod / 2 ? 0.0 : 1.0;
    // Each joint circles at its own radius: every frame-to-frame step of the cycle has the same
    // length, so "no larger than the largest step" is sharp at the seam.
    for (int j = 0; j < kJoints; ++j) {
      w.local(t, 3 * j) = (1 + j) * std::sin(phase + j);
      w.local(t, 3 * j + 1) = 10.0 + drift * t;
      w.local(t, 3 * j + 2) = (1 + j) * std::cos(phase + j);
    }
    w.ground(t, 0) = kSpeed * t;
    w.ground(t, 1) = 0.0;
  }
  return w;
}

double largest_step(const Eigen::MatrixXd& x) {
  double most = 0.0;
  for (Eigen::Index t = 1; t < x.rows(); ++t) most = std::max(most, (x.row(t) - x.row(t - 1)).norm());
  return most;
}

}  // namespace

TEST_CASE("loop: find_loop cuts whole cycles at left-foot strikes", "[loop]") {
  for (double drift : {0.0, kDrift}) {
    INFO("drift " << drift);
    const Walk w = periodic_walk(drift);
    const LoopCut cut = find_loop(w.contacts, w.local, w.heading);
    INFO("cut " << cut.begin << ".." << cut.end << ", " << cut.cycles << " cycles");
    CHECK(cut.cycles >= 1);
    CHECK(cut.cycles <= kLoopMaxCycles);
    CHECK(cut.frames() == cut.cycles * kPeriod);
    CHECK((cut.begin - kOffset) % kPeriod == 0);  // at a left-foot strike
    CHECK(cut.begin >= kOffset);
    CHECK(cut.end < kFrames);
    CHECK(w.contacts(cut.begin, 0) == 1.0);
    CHECK(w.contacts(cut.begin - 1, 0) == 0.0);
  }
}

TEST_CASE("loop: close_loop makes the seam no larger than any step of the cycle", "[loop]") {
  Walk w = periodic_walk();
  LoopCut cut = find_loop(w.contacts, w.local, w.heading);
  const int n = cut.frames();
  REQUIRE(n > 0);
  const double seam_before = (w.local.row(cut.end) - w.local.row(cut.begin)).norm();
  REQUIRE(seam_before > 0);  // the drift leaves a gap to close
  const Eigen::MatrixXd contacts_before = w.contacts.middleRows(cut.begin, n);
  close_loop(cut, w.local, w.ground, w.heading, w.contacts);
  REQUIRE(w.local.rows() == n);
  REQUIRE(w.ground.rows() == n);
  REQUIRE(w.heading.size() == n);
  REQUIRE(w.contacts.rows() == n);
  CHECK(w.contacts == contacts_before);
  // Played on repeat, the last frame leads into the first as any frame into the next.
  const double seam = (w.local.row(0) - w.local.row(n - 1)).norm();
  INFO("seam " << seam << " (gap before " << seam_before << "), largest step " << largest_step(w.local));
  CHECK(seam <= largest_step(w.local) * (1.0 + kExact));
  // Root motion: the travel of the whole cycles at constant speed; the heading did not turn.
  CHECK(cut.travel.x() == Approx(kSpeed * n).epsilon(kExact));
  CHECK(cut.travel.y() == Approx(0.0).margin(kExact * kSpeed * n));
  CHECK(cut.turn_removed == Approx(0.0).margin(kExact));
  CHECK((w.heading.array() - kHeading).abs().maxCoeff() < kExact);
  // The ground starts where the cut began and keeps the speed.
  CHECK(w.ground(0, 0) == Approx(kSpeed * cut.begin).epsilon(kExact));
  for (int t = 1; t < n; ++t) CHECK(w.ground(t, 0) - w.ground(t - 1, 0) == Approx(kSpeed).epsilon(kExact));
}

TEST_CASE("loop: a turning cycle has its turn spread out", "[loop]") {
  Walk w = periodic_walk();
  for (int t = 0; t < kFrames; ++t) w.heading[t] = kHeading + 0.001 * t;  // a gentle curve
  LoopCut cut = find_loop(w.contacts, w.local, w.heading);
  const double turn = w.heading[cut.end] - w.heading[cut.begin];
  close_loop(cut, w.local, w.ground, w.heading, w.contacts);
  CHECK(cut.turn_removed == Approx(turn).epsilon(1e-9));
  // The loop walks straight: its heading comes back to where it started.
  CHECK(std::abs(w.heading[w.heading.size() - 1] - w.heading[0]) < std::abs(turn));
}

TEST_CASE("loop: fewer than two strikes of either foot throws InputError", "[loop]") {
  const Walk w = periodic_walk();
  SECTION("no strikes at all") {
    const Eigen::MatrixXd planted = Eigen::MatrixXd::Ones(kFrames, 2);
    CHECK_THROWS_AS(find_loop(planted, w.local, w.heading), InputError);
    CHECK_THROWS_AS(find_loop(Eigen::MatrixXd::Zero(kFrames, 2), w.local, w.heading), InputError);
  }
  SECTION("one strike of each foot") {
    Eigen::MatrixXd one = Eigen::MatrixXd::Zero(kFrames, 2);
    one.block(10, 0, 5, 1).setOnes();
    one.block(30, 1, 5, 1).setOnes();
    CHECK_THROWS_WITH(find_loop(one, w.local, w.heading), Catch::Contains("fewer than two foot strikes"));
  }
  SECTION("two strikes of the right foot only: the right foot's cycle") {
    Eigen::MatrixXd right = Eigen::MatrixXd::Zero(kFrames, 2);
    right.block(20, 1, 5, 1).setOnes();
    right.block(44, 1, 5, 1).setOnes();
    const LoopCut cut = find_loop(right, w.local, w.heading);
    CHECK(cut.begin == 20);
    CHECK(cut.end == 44);
    CHECK(cut.cycles == 1);
  }
  SECTION("a cut outside the motion") {
    Walk copy = w;
    LoopCut bad;
    bad.begin = 10;
    bad.end = kFrames;
    CHECK_THROWS_AS(close_loop(bad, copy.local, copy.ground, copy.heading, copy.contacts), InputError);
  }
}
