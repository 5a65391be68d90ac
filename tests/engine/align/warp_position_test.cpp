// A common timeline's samples found on the warps it was made of (engine/align/warp_position.h):
// worked by hand, and against the warp's own samples on random warps.
#include "engine/align/warp_position.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <random>

#include "tests/engine/align/made_warps.h"

using namespace mostyle;
using test::random_warp;
using test::warp_of;

TEST_CASE("warp position: a timeline sample found on its warp, worked by hand") {
  // Samples of the warp at reference 0.5, 1.5, 2.2, 3; the timeline's at 0.5, 1, 1.5, 2, 2.5, 3
  // (common_timeline_test.cpp). Reference 1 (B 0.5) is halfway between the warp's first two
  // samples; reference 2 (B 1 + 0.5 / 0.7) is 0.5 / 0.7 of the way from its second to its third.
  const TimeWarp w = warp_of({0.5, 1.5, 2.2, 3}, {0, 1, 2, 3});
  const CommonTimeline t = common_timeline({&w});
  REQUIRE(t.samples() == 6);
  CHECK(warp_position(w, t, 1, 0.0) == Approx(0.0));
  CHECK(warp_position(w, t, 1, 1.0) == Approx(0.5));
  CHECK(warp_position(w, t, 1, 2.0) == Approx(1.0));
  CHECK(warp_position(w, t, 1, 3.0) == Approx(1.0 + 0.5 / 0.7));
  CHECK(warp_position(w, t, 1, 5.0) == Approx(3.0));
  CHECK(warp_position(w, t, 1, 0.5) == Approx(0.25));  // between timeline samples, linearly
  // Outside the timeline, clamped; a take the timeline lacks, 0.
  CHECK(warp_position(w, t, 1, -3.0) == 0.0);
  CHECK(warp_position(w, t, 1, 99.0) == Approx(3.0));
  CHECK(warp_position(w, t, 2, 1.0) == 0.0);
}

TEST_CASE("warp position: every sample of random warps is found where it is") {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const TimeWarp w = random_warp(rng, 60);
    const CommonTimeline t = common_timeline({&w});
    for (int s = 0; s < t.samples(); ++s) {
      const double u = warp_position(w, t, 1, s);
      REQUIRE(u >= 0.0);
      REQUIRE(u <= w.samples() - 1.0);
      // The warp read at that position gives the timeline's frames back.
      const Eigen::Index i = std::min<Eigen::Index>(static_cast<Eigen::Index>(u), w.samples() - 2);
      const double f = u - double(i);
      CHECK(w.a[i] + f * (w.a[i + 1] - w.a[i]) == Approx(t.frames[0][s]).margin(1e-9));
      CHECK(w.b[i] + f * (w.b[i + 1] - w.b[i]) == Approx(t.frames[1][s]).margin(1e-9));
    }
  }
}
