#include "engine/align/common_timeline.h"

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "engine/base/error.h"
#include "tests/engine/align/made_warps.h"

using namespace mostyle;
using test::random_warp;
using test::warp_of;

namespace {

// Brute force: b at reference frame r by scanning every segment.
double brute_at(const TimeWarp& w, double r) {
  for (int s = 0; s + 1 < w.samples(); ++s)
    if (w.a[s] <= r && r <= w.a[s + 1] && w.a[s + 1] > w.a[s]) {
      // the last segment that contains r, as the reader moves on at a segment's end
      int last = s;
      while (last + 2 < w.samples() && w.a[last + 1] <= r && w.a[last + 2] > w.a[last + 1] && r >= w.a[last + 1])
        ++last;
      const double f = (r - w.a[last]) / (w.a[last + 1] - w.a[last]);
      return w.b[last] + std::clamp(f, 0.0, 1.0) * (w.b[last + 1] - w.b[last]);
    }
  return r <= w.a[0] ? w.b[0] : w.b[w.samples() - 1];
}

}  // namespace

// Whether every whole reference frame from the timeline's first sample to its last is one of its
// samples (so a take read at the reference's own frames is read on its frames, not between).
bool whole_frames_sampled(const CommonTimeline& t) {
  const Eigen::VectorXd& r = t.frames[0];
  for (double f = std::ceil(r[0] - 1e-9); f <= r[r.size() - 1] + 1e-9; f += 1.0)
    if ((r.array() - f).abs().minCoeff() > 1e-9) return false;
  return true;
}

TEST_CASE("one warp on whole frames, no take faster than one frame a sample, is its own common timeline") {
  const TimeWarp w = warp_of({0, 1, 2, 2.5, 3}, {0, 0.5, 1.5, 2.5, 3.5});
  const CommonTimeline t = common_timeline({&w});
  REQUIRE(t.takes() == 2);
  CHECK(t.frames[0] == w.a);
  CHECK(t.frames[1] == w.b);
}

TEST_CASE("one warp's common timeline has the reference's whole frames among its samples") {
  // Reference 0.5 to 3: knots at 1, 2 and 3. Over 1..2 the warp's steepest segment (1.5 to 2.2,
  // B one frame in 0.7) runs 1 / 0.7 B frames a reference frame: two steps there, and over 2..3
  // (slopes 1 / 0.7 and 1 / 0.8) two more, B read on the warp's line at each.
  const TimeWarp w = warp_of({0.5, 1.5, 2.2, 3}, {0, 1, 2, 3});
  const CommonTimeline t = common_timeline({&w});
  REQUIRE(t.samples() == 6);
  const std::vector<double> a{0.5, 1, 1.5, 2, 2.5, 3}, b{0, 0.5, 1, 1 + 0.5 / 0.7, 2 + 0.3 / 0.8, 3};
  for (int s = 0; s < 6; ++s) {
    CHECK(t.frames[0][s] == Approx(a[static_cast<size_t>(s)]).margin(1e-12));
    CHECK(t.frames[1][s] == Approx(b[static_cast<size_t>(s)]).margin(1e-12));
  }
  CHECK(t.first == std::vector<int>{0, 0});
  CHECK(t.last == std::vector<int>{5, 5});
}

TEST_CASE("a hand-worked common timeline of two warps") {
  // Take 1 runs with the reference over 0..10; take 2 matches reference frames 2..8 at twice
  // its speed. The timeline covers 0..10; over 2..8 it steps by half a frame so take 2 moves one
  // frame a sample; outside, take 2 holds its first or last matched frame.
  const TimeWarp one = warp_of({0, 10}, {0, 10});
  const TimeWarp two = warp_of({2, 8}, {4, 16});
  const CommonTimeline t = common_timeline({&one, &two});
  REQUIRE(t.takes() == 3);
  CHECK(t.frames[0][0] == 0.0);
  CHECK(t.frames[0][t.samples() - 1] == 10.0);
  CHECK(t.first[1] == 0);
  CHECK(t.last[1] == t.samples() - 1);
  REQUIRE(t.frames[0][t.first[2]] == Approx(2.0));
  REQUIRE(t.frames[0][t.last[2]] == Approx(8.0));
  CHECK(t.last[2] - t.first[2] == 12);
  for (int s = 0; s < t.samples(); ++s) {
    const double r = t.frames[0][s];
    CHECK(t.frames[1][s] == Approx(r));
    CHECK(t.frames[2][s] == Approx(std::clamp(2.0 * r, 4.0, 16.0)));
    if (s > 0) CHECK(t.frames[2][s] - t.frames[2][s - 1] <= 1.0 + 1e-9);
  }
}

TEST_CASE("a hand-worked common timeline with holds of the reference") {
  // Take 1 plays frames 0..3 while the reference holds its frame 0 (a rest the reference lacks),
  // then both run together to 6, then take 1 plays 2.5 frames more with the reference held on
  // its last frame. Take 2 runs with the reference and stays still over both holds.
  const TimeWarp one = warp_of({0, 0, 0, 0, 1, 2, 3, 4, 5, 6, 6, 6}, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11.5});
  const TimeWarp two = warp_of({0, 6}, {0, 6});
  const CommonTimeline t = common_timeline({&one, &two});
  const std::vector<double> reference{0, 0, 0, 0, 1, 2, 3, 4, 5, 6, 6, 6, 6};
  const std::vector<double> first{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9 + 2.5 / 3, 9 + 5.0 / 3, 11.5};
  const std::vector<double> second{0, 0, 0, 0, 1, 2, 3, 4, 5, 6, 6, 6, 6};
  REQUIRE(t.samples() == static_cast<int>(reference.size()));
  for (int s = 0; s < t.samples(); ++s) {
    CHECK(t.frames[0][s] == Approx(reference[static_cast<size_t>(s)]));
    CHECK(t.frames[1][s] == Approx(first[static_cast<size_t>(s)]));
    CHECK(t.frames[2][s] == Approx(second[static_cast<size_t>(s)]));
  }
  CHECK(t.first == std::vector<int>{0, 0, 0});
  CHECK(t.last == std::vector<int>{12, 12, 12});
}

TEST_CASE("common timelines of random warps against brute force") {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 100; ++trial) {
    const int takes = 2 + trial % 5;
    std::vector<TimeWarp> warps;
    for (int i = 0; i < takes; ++i) warps.push_back(random_warp(rng, 40 + trial % 30));
    std::vector<const TimeWarp*> pointers;
    for (const TimeWarp& w : warps) pointers.push_back(&w);
    const CommonTimeline t = common_timeline(pointers);
    REQUIRE(t.takes() == takes + 1);
    CHECK(whole_frames_sampled(t));
    const CommonTimeline alone = common_timeline({pointers[0]});
    CHECK(whole_frames_sampled(alone));
    for (int s = 0; s < alone.samples(); ++s)
      CHECK(alone.frames[1][s] == Approx(brute_at(warps[0], alone.frames[0][s])).margin(1e-9));
    for (int i = 0; i < takes; ++i) {
      // Each warp's matched range is a stretch of samples, its ends among them.
      CHECK(t.frames[0][t.first[i + 1]] == Approx(warps[i].a[0]).margin(1e-9));
      CHECK(t.frames[0][t.last[i + 1]] == Approx(warps[i].a[warps[i].samples() - 1]).margin(1e-9));
    }
    for (int s = 0; s < t.samples(); ++s)
      for (int i = 0; i < takes; ++i) CHECK(t.frames[i + 1][s] == Approx(brute_at(warps[i], t.frames[0][s])).margin(1e-9));
    for (int s = 1; s < t.samples(); ++s)
      for (int i = 0; i <= takes; ++i) {
        const double step = t.frames[i][s] - t.frames[i][s - 1];
        CHECK(step >= -1e-12);
        CHECK(step <= 1.0 + 1e-9);  // no take skips a frame
      }
  }
}

TEST_CASE("a common timeline needs warps with samples") {
  const TimeWarp empty;
  CHECK_THROWS_AS(common_timeline({&empty}), InputError);
  CHECK_THROWS_AS(common_timeline({}), InputError);
}
