// An alignment's warnings (engine/align/alignment.h) name the takes and count frames as their
// files do, worked out by hand.
#include "engine/align/alignment.h"

#include <catch2/catch.hpp>

using namespace mostyle;

TEST_CASE("alignment warnings: takes by name, frames in each file's own rate") {
  Alignment al;
  al.feature.on = AlignOn::kLeftFoot;
  // 11 samples at 30 fps: A frames 0..10, B frames 100..120 (B runs twice as fast).
  al.warp.a = Eigen::VectorXd::LinSpaced(11, 0.0, 10.0);
  al.warp.b = Eigen::VectorXd::LinSpaced(11, 100.0, 120.0);
  al.cost_ratio = Eigen::VectorXd::Constant(11, 1.0);
  al.cost_ratio.segment(4, 3).setConstant(5.0);
  al.poor = {{4, 6}};
  al.a_first = 0, al.a_last = 10, al.b_first = 100, al.b_last = 120;
  al.frames_a = 11, al.frames_b = 300;  // only 21 of B's 300 frames are matched
  // The pair as the pipeline names it: A and B, whose files run at 120 and 30 fps.
  const std::vector<std::string> pair = alignment_warnings(al, 30.0, {"A", 120.0}, {"B", 30.0});
  REQUIRE(pair.size() == 2);
  CHECK(pair[0] ==
        "A's frames 16-24 (0.1 s to 0.2 s) match B's frames 108-112 poorly: the left-foot differ 5.0 times as much as "
        "along the rest of the alignment");
  CHECK(pair[1] == "only B's frames 100-120 (0.7 s of 10.0 s) match the other take; the rest is left out");
  // A palette's third take, by its file's name.
  const std::vector<std::string> named = alignment_warnings(al, 30.0, {"normal.bvh", 30.0}, {"tired.bvh", 120.0});
  CHECK(named[1] == "only tired.bvh's frames 400-480 (0.7 s of 10.0 s) match normal.bvh; the rest is left out");
  // 0: frames at the working rate.
  CHECK(alignment_warnings(al, 30.0, {"A", 0.0}, {"B", 0.0})[1].find("frames 100-120") != std::string::npos);
}
