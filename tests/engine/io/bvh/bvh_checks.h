#pragma once
// Checks the BVH reader's and writer's tests share.
#include <catch2/catch.hpp>
#include <string>

#include "engine/base/clip.h"

namespace mostyle::test {

inline std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

inline void check_same_clip(const Clip& a, const Clip& b) {
  REQUIRE(a.skeleton.joints.size() == b.skeleton.joints.size());
  for (size_t i = 0; i < a.skeleton.joints.size(); ++i) {
    const Joint& x = a.skeleton.joints[i];
    const Joint& y = b.skeleton.joints[i];
    CHECK(x.name == y.name);
    CHECK(x.parent == y.parent);
    CHECK(x.offset == y.offset);
    CHECK(x.channels == y.channels);
    CHECK(x.first_channel == y.first_channel);
    CHECK(x.end_site == y.end_site);
  }
  CHECK(a.skeleton.channel_count == b.skeleton.channel_count);
  CHECK(a.frame_time == b.frame_time);
  CHECK(a.motion == b.motion);
}

}  // namespace mostyle::test
