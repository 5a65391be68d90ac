// Cycles moved to a phase and loops read across their end (engine/align/cycle_phase.h), worked by
// hand.
#include <cmath>

#include <catch2/catch.hpp>

#include "engine/align/cycle_phase.h"
#include "engine/base/error.h"

using namespace mostyle;

TEST_CASE("cycle phase: cycles begun at strikes moved to begin a fraction of a cycle before them") {
  TakeCycles take;
  take.kind = CycleKind::kGait;
  take.foot = 0;
  take.cycles = {{10, 30}, {30, 50}, {60, 80}};  // strikes at 10, 30, 50 (meeting), then 60
  const TakeCycles moved = cycles_at_phase(take, 0.25, 100);
  CHECK(moved.strike_phase == 0.25);
  REQUIRE(moved.cycles.size() == 3);
  CHECK(moved.cycles[0].begin == 5);   // 10 - 0.25 x 20
  CHECK(moved.cycles[0].end == 25);    // meets the next, moved as it is
  CHECK(moved.cycles[1].begin == 25);
  CHECK(moved.cycles[1].end == 45);    // its own length on: the cycle after does not meet it
  CHECK(moved.cycles[2].begin == 55);
  CHECK(moved.cycles[2].end == 75);
  // Each moved cycle has its strike at a quarter of it.
  for (size_t k = 0; k < moved.cycles.size(); ++k)
    CHECK(take.cycles[k].begin - moved.cycles[k].begin == Approx(0.25 * moved.cycles[k].frames()));
}

TEST_CASE("cycle phase: a cycle that would leave the take is dropped, or moved a cycle on when it is the only one") {
  TakeCycles take;
  take.kind = CycleKind::kGait;
  take.cycles = {{4, 24}, {24, 44}};
  // Moved back by half a cycle the first begins at -6: dropped; the second fits.
  TakeCycles moved = cycles_at_phase(take, 0.5, 60);
  REQUIRE(moved.cycles.size() == 1);
  CHECK(moved.cycles[0].begin == 14);
  CHECK(moved.cycles[0].end == 34);
  // One cycle only, with no room before it: moved half a cycle on instead.
  take.cycles = {{4, 24}};
  moved = cycles_at_phase(take, 0.5, 40);
  REQUIRE(moved.cycles.size() == 1);
  CHECK(moved.cycles[0].begin == 14);
  CHECK(moved.cycles[0].end == 34);
  // No room either way: none, and why.
  moved = cycles_at_phase(take, 0.5, 30);
  CHECK(moved.cycles.empty());
  CHECK(moved.kind == CycleKind::kNone);
  CHECK_FALSE(moved.reason.empty());
}

TEST_CASE("cycle phase: a loop's strike inside it moves its window to the reference's phase") {
  TakeCycles loop;
  loop.kind = CycleKind::kGait;
  loop.loop_frames = 20;
  loop.strike_phase = 0.6;          // its foot lands at frame 12 of each repeat
  loop.cycles = {{40, 60}};         // its third repeat, unrolled
  const TakeCycles moved = cycles_at_phase(loop, 0.1, 100);
  REQUIRE(moved.cycles.size() == 1);
  CHECK(moved.cycles[0].begin == 50);  // the strike at 52, 2 frames (0.1 of 20) after the window begins
  CHECK(moved.cycles[0].end == 70);
}

TEST_CASE("cycle phase: a loop unrolled repeats its poses and contacts, its root walking on") {
  CanonicalMotion take;
  const int frames = 5;
  take.local.resize(frames, 3);
  take.ground.resize(frames, 2);
  take.heading = Eigen::VectorXd::Zero(frames);
  Eigen::MatrixXd contacts = Eigen::MatrixXd::Zero(frames, 2);
  for (int f = 0; f < frames; ++f) {
    take.local.row(f) << f, 10.0 * f, 0.0;
    take.ground.row(f) << 0.0, 2.0 * f;  // walking +Z, 2 units a frame
    contacts(f, f % 2) = 1.0;
  }
  // The first frame would follow the last: the loop is the whole take.
  UnrolledLoop u = unroll_loop(take, contacts, 5, 3);
  REQUIRE(u.motion.local.rows() == 15);
  for (int v = 0; v < 15; ++v) {
    CHECK(u.motion.local(v, 0) == v % 5);
    CHECK(u.contacts(v, v % 5 % 2) == 1.0);
    CHECK(u.motion.ground(v, 1) == Approx(2.0 * v));  // the step out of the last frame: the one before it
  }
  // The last frame repeats the first: a loop of 4.
  u = unroll_loop(take, contacts, 4, 2);
  REQUIRE(u.motion.local.rows() == 8);
  CHECK(u.motion.local(4, 0) == 0.0);
  CHECK(u.motion.local(7, 0) == 3.0);
  CHECK(u.motion.ground(7, 1) == Approx(14.0));
  CHECK_THROWS_AS(unroll_loop(take, contacts, 3, 2), InputError);
  CHECK_THROWS_AS(unroll_loop(take, contacts, 5, 0), InputError);
}
