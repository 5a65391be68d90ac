#include "engine/trajectory/mixed_trajectory.h"

#include <catch2/catch.hpp>

#include "engine/base/error.h"

using namespace mostyle;

namespace {

// Three takes on a common timeline of 10 samples: take i at frame 2 k + i at sample k, matched
// over samples [0, 9], [2, 7] and [5, 9]; their fastest joints 1, 2 and 3 units per second.
PreparedTakes three_takes() {
  PreparedTakes p;
  p.takes.resize(3);
  for (int i = 0; i < 3; ++i) {
    p.timeline.frames.push_back(2.0 * Eigen::VectorXd::LinSpaced(10, 0.0, 9.0).array() + i);
    p.takes[static_cast<size_t>(i)].fastest_joint = i + 1.0;
  }
  p.timeline.first = {0, 2, 5};
  p.timeline.last = {9, 7, 9};
  return p;
}

}  // namespace

TEST_CASE("mixed trajectory: the stretch played is where every weighted take matches, worked by hand",
          "[mixed_trajectory]") {
  const PreparedTakes p = three_takes();
  const Eigen::MatrixXd none;
  SECTION("a take at weight 0 does not shorten it") {
    const PlayedStretch st = played_stretch(p, {0.5, 0.5, 0.0}, {}, none, false, {0.5, 0.5, 0.0});
    CHECK(st.first == 2);
    CHECK(st.last == 7);
    CHECK(st.length() == 6);
    CHECK(st.fastest == 2.0);
  }
  SECTION("every take weighted: their common part") {
    const PlayedStretch st = played_stretch(p, {0.2, 0.3, 0.5}, {}, none, false, {0.2, 0.3, 0.5});
    CHECK(st.first == 5);
    CHECK(st.last == 7);
    CHECK(st.fastest == 3.0);
  }
  SECTION("a take with timing weight only, a key or a part weight counts") {
    CHECK(played_stretch(p, {1.0, 0.0, 0.0}, {}, none, false, {0.0, 0.0, 1.0}).first == 5);
    WeightKeys keys(1);
    keys[0].weights = {0.0, 1.0, 0.0};
    CHECK(played_stretch(p, {1.0, 0.0, 0.0}, keys, none, false, {1.0, 0.0, 0.0}).first == 2);
    Eigen::MatrixXd parts(2, 3);
    parts << 1, 0, 0,  //
        0, 0, 1;
    CHECK(played_stretch(p, {1.0, 0.0, 0.0}, {}, parts, true, {1.0, 0.0, 0.0}).first == 5);
  }
  SECTION("takes matched apart: an error") {
    PreparedTakes apart = p;
    apart.timeline.last[2] = 9;
    apart.timeline.first[1] = 0;
    apart.timeline.last[1] = 4;
    CHECK_THROWS_AS(played_stretch(apart, {0.0, 0.5, 0.5}, {}, none, false, {0.0, 0.5, 0.5}), InputError);
  }
}

TEST_CASE("mixed trajectory: each take's frame at the output frames, worked by hand", "[mixed_trajectory]") {
  const PreparedTakes p = three_takes();
  RowSampler at;
  Eigen::VectorXd t(3);
  t << 0.0, 1.5, 3.0;  // samples 2, 3.5 and 5 of a stretch from sample 2
  at.set(t, 6);
  Eigen::MatrixXd sources;
  write_sources(p, at, 2, sources);
  Eigen::MatrixXd expected(3, 3);
  expected << 4, 5, 6,  //
      7, 8, 9,          //
      10, 11, 12;
  CHECK(sources == expected);
}
