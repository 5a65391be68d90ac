// Registration by cycles, first part (engine/align/cycle_registration.h): a short take's cycles
// reused in order over a long reference, each reference frame inside a cycle at the same phase of
// its matched cycle, nothing outside the reference's cycles; and on real walks of different
// lengths, the whole of the reference's cycles covered.
#include <cmath>
#include <memory>

#include <catch2/catch.hpp>

#include "engine/align/cycle_registration.h"
#include "engine/io/error.h"
#include "engine/io/motion_file.h"
#include "engine/run/prepare_takes.h"
#include "tests/test_data.h"

using namespace mostyle;

TEST_CASE("cycle registration: a short take's cycles reused in order, phases matched, worked by hand") {
  TakeCycles reference, take;
  reference.cycles = {{10, 40}, {40, 70}, {80, 100}, {100, 130}, {130, 160}};  // a pause at 70-80
  take.cycles = {{0, 15}, {15, 33}};
  const std::vector<int> pairs = pair_cycles(reference, take);
  CHECK(pairs == std::vector<int>{0, 1, 0, 1, 0});
  const Eigen::VectorXd f = frames_by_cycles(reference, take, pairs, 170);
  CHECK(std::isnan(f[0]));
  CHECK(std::isnan(f[9]));
  CHECK(f[10] == 0.0);
  CHECK(f[25] == Approx(7.5));      // half way through reference cycle 1: half way through take cycle 1
  CHECK(f[40] == 15.0);             // cycle 2 begins where take cycle 2 does
  CHECK(f[69] == Approx(15 + 29 * 18.0 / 30));
  CHECK(std::isnan(f[75]));         // the pause: no match, posture only
  CHECK(f[80] == 0.0);              // the take's first cycle again
  CHECK(f[90] == Approx(7.5));      // a 20-frame reference cycle: the take's 15 frames at 3/4 speed
  CHECK(std::isnan(f[165]));
  // Every frame inside a reference cycle is matched, inside its matched cycle.
  for (size_t k = 0; k < reference.cycles.size(); ++k)
    for (int i = reference.cycles[k].begin; i < reference.cycles[k].end; ++i) {
      const Cycle& c = take.cycles[static_cast<size_t>(pairs[k])];
      CHECK(f[i] >= c.begin);
      CHECK(f[i] < c.end);
    }
  // Nothing to pair: no cycles on either side.
  CHECK(pair_cycles(reference, TakeCycles()).empty());
  CHECK(pair_cycles(TakeCycles(), take).empty());
  CHECK_THROWS_AS(frames_by_cycles(reference, take, {0, 1}, 170), InputError);
  CHECK_THROWS_AS(frames_by_cycles(reference, take, {0, 1, 2, 0, 1}, 170), InputError);
  CHECK_THROWS_AS(frames_by_cycles(reference, take, pairs, 150), InputError);
}

TEST_CASE("cycle registration: a 6.5 s walk covers every cycle of a 22 s one") {
  const auto content = std::make_shared<const Clip>(read_motion_file(test::shared_motion("cmu142_walk_joy.bvh")));
  const auto neutral = std::make_shared<const Clip>(read_motion_file(test::shared_motion("bandai_walk_normal.bvh")));
  const auto p = prepare_takes(std::vector<std::shared_ptr<const Clip>>{content, neutral}, PrepareOptions());
  const TakeCycles& ref = p->takes[0].cycles;
  const TakeCycles& other = p->takes[1].cycles;
  REQUIRE(ref.cycles.size() > other.cycles.size());  // the style take is the shorter
  const std::vector<int> pairs = pair_cycles(ref, other);
  const int frames = static_cast<int>(p->takes[0].canonical.local.rows());
  const Eigen::VectorXd f = frames_by_cycles(ref, other, pairs, frames);
  int matched = 0;
  for (int i = 0; i < frames; ++i) matched += std::isnan(f[i]) ? 0 : 1;
  CHECK(matched == ref.frames_in_cycles());
  // Every cycle of the short take is used, in order, more than once.
  for (size_t k = 0; k < pairs.size(); ++k) CHECK(pairs[k] == static_cast<int>(k % other.cycles.size()));
  CHECK(pairs.size() >= 2 * other.cycles.size());
}
