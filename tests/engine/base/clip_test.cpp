#include "engine/base/clip.h"

#include <catch2/catch.hpp>

using namespace mostyle;

TEST_CASE("frame rate snaps near-whole rates and keeps others", "[clip]") {
  CHECK(frame_rate_from_frame_time(0.008333) == 120.0);
  CHECK(frame_rate_from_frame_time(0.0333333) == 30.0);
  CHECK(frame_rate_from_frame_time(0.01) == 100.0);
  CHECK(frame_rate_from_frame_time(1.0 / 29.97) == Approx(29.97));
  CHECK(frame_rate_from_frame_time(0.0) == 0.0);
}

TEST_CASE("skeleton lookups skip End Sites", "[clip]") {
  Skeleton s;
  s.joints.push_back({"Hips", -1});
  s.joints.push_back({"Hips End Site", 0});
  s.joints.back().end_site = true;
  s.joints.push_back({"Spine", 0});
  CHECK(s.find("Spine") == 2);
  CHECK(s.find("Hips End Site") == -1);
  CHECK(s.joint_count_without_end_sites() == 2);
  CHECK(s.children(0) == std::vector<int>{1, 2});
}
