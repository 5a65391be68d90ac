#include "engine/io/motion_file.h"

#include <catch2/catch.hpp>

#include "engine/base/error.h"
#include "tests/test_data.h"

using namespace mostyle;
using Catch::Matchers::Contains;

TEST_CASE("motion_format and FILE#ANIMATION", "[motion_file]") {
  CHECK(motion_format("a/walk.BVH") == MotionFormat::kBvh);
  CHECK(motion_format("walk.Fbx") == MotionFormat::kFbx);
  CHECK(motion_format("walk.glb") == MotionFormat::kGltf);
  CHECK(motion_format("walk.gltf") == MotionFormat::kGltf);
  CHECK(motion_format("walk") == MotionFormat::kBvh);
  CHECK(is_motion_file("x/y.glb"));
  CHECK_FALSE(is_motion_file("x/y.txt"));
  CHECK(split_take_path("walks.glb#run").path == "walks.glb");
  CHECK(split_take_path("walks.glb#run").take == "run");
  CHECK(split_take_path("dir#1/walks.fbx#Take 001").path == "dir#1/walks.fbx");
  CHECK(split_take_path("dir#1/walks.fbx#Take 001").take == "Take 001");
  CHECK(split_take_path("walk#2.bvh").path == "walk#2.bvh");  // a BVH has no takes: '#' is in the name
  CHECK(split_take_path("walk.bvh#x").take.empty());
  CHECK(join_take_path("a.glb", "run") == "a.glb#run");
  CHECK(join_take_path("a.bvh", "") == "a.bvh");
  CHECK(take_label("data/walks.glb#run") == "run");
  CHECK(take_label("data/walk.bvh") == "walk");
}

TEST_CASE("read_motion_file: BVH through the BVH reader, a take of a BVH is an error", "[motion_file]") {
  const std::string file = test::asset("motions/cmu142_walk_clumsy.bvh");
  CHECK(read_motion_file(file).frames() == 1080);
  MotionReadOptions o;
  o.take = "run";
  CHECK_THROWS_WITH(read_motion_file(file, nullptr, o), Contains("a BVH file holds one take, so it has no animation 'run'"));
  const std::vector<TakeInfo> takes = read_motion_takes(file);
  REQUIRE(takes.size() == 1);
  CHECK(takes[0].name == "cmu142_walk_clumsy");
  CHECK(takes[0].keyframes == 1080);
}

TEST_CASE("take labels: what differs between the takes, for narrow columns", "[motion_file]") {
  using V = std::vector<std::string>;
  CHECK(distinct_take_labels({"a/cmu142_walk_happy.bvh", "b/cmu142_walk_marching.bvh", "cmu142_walk_joy.fbx"}) ==
        V{"happy", "marching", "joy"});
  // The shared start ends at a '_' or '-': "walk_h" and "walk_ha" keep their words whole.
  CHECK(distinct_take_labels({"walk_happy.bvh", "walk_hasty.bvh"}) == V{"happy", "hasty"});
  CHECK(distinct_take_labels({"walks.glb#run-fast", "walks.glb#run-slow"}) == V{"fast", "slow"});
  // A label that is all shared start keeps every label whole; nothing shared, nothing cut; one take as it is.
  CHECK(distinct_take_labels({"walk.bvh", "walk_old.bvh"}) == V{"walk", "walk_old"});
  CHECK(distinct_take_labels({"normal.bvh", "tired.bvh"}) == V{"normal", "tired"});
  CHECK(distinct_take_labels({"cmu142_walk_happy.bvh"}) == V{"cmu142_walk_happy"});
  CHECK(distinct_take_labels({"x_a.bvh", "x_a.bvh"}) == V{"x_a", "x_a"});
}
