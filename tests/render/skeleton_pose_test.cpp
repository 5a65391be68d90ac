#include "render/skeleton_pose.h"

#include <catch2/catch.hpp>

#include "render/skeleton_renderer.h"

using namespace mostyle::render;

namespace {
SkeletonPose chain() {
  SkeletonPose pose;
  pose.label = "chain";
  pose.positions = {{0, 0.2f, 0}, {0, 1.0f, 0}, {0, 1.8f, 0}};
  pose.parents = {-1, 0, 1};
  pose.size = 2.0f;
  return pose;
}
}  // namespace

TEST_CASE("positions_at reads one frame row as vec3 per joint") {
  Eigen::MatrixXd m(2, 6);
  m << 1, 2, 3, 4, 5, 6,  //
      7, 8, 9, 10, 11, 12;
  std::vector<glm::vec3> p = positions_at(m, 1);
  REQUIRE(p.size() == 2);
  CHECK(p[0] == glm::vec3(7, 8, 9));
  CHECK(p[1] == glm::vec3(10, 11, 12));
}

TEST_CASE("parent_indices follows the engine skeleton, End Sites included") {
  mostyle::Skeleton s;
  s.joints.resize(4);
  s.joints[0].parent = -1;
  s.joints[1].parent = 0;
  s.joints[2].parent = 1;
  s.joints[3].parent = 0;
  s.joints[3].end_site = true;
  CHECK(parent_indices(s) == std::vector<int>{-1, 0, 1, 0});
}

TEST_CASE("is_valid rejects mismatched sizes and forward parents") {
  SkeletonPose pose = chain();
  std::string why;
  CHECK(is_valid(pose, &why));
  pose.parents[1] = 2;
  CHECK_FALSE(is_valid(pose, &why));
  CHECK_THAT(why, Catch::Contains("joint 1"));
  pose = chain();
  pose.parents.pop_back();
  CHECK_FALSE(is_valid(pose));
  pose = chain();
  pose.highlights.resize(2);
  CHECK_FALSE(is_valid(pose));
  pose = chain();
  pose.contacts.resize(1);
  CHECK_FALSE(is_valid(pose));
}

TEST_CASE("clip_bounds holds every joint of every frame") {
  Eigen::MatrixXd m(2, 6);
  m << 0, 0, 0, 0, 170, 0,  // a 170-unit standing pose
      50, 10, 0, 50, 100, 0;  // crouched and moved
  Bounds b = clip_bounds(m);
  CHECK(b.min == glm::vec3(0, 0, 0));
  CHECK(b.max == glm::vec3(50, 170, 0));
}

TEST_CASE("effective_size and label_anchor") {
  SkeletonPose pose = chain();
  CHECK(effective_size(pose) == 2.0f);
  pose.size = 0.0f;
  CHECK(effective_size(pose) == Approx(1.6f));
  glm::vec3 anchor = label_anchor(pose);
  CHECK(anchor.y > 1.8f);
  CHECK(anchor.x == 0.0f);
}

TEST_CASE("mark_ground_contacts flags joints near the floor") {
  SkeletonPose pose = chain();
  mark_ground_contacts(&pose, 0.15f, 0.1f);
  CHECK(pose.contacts == std::vector<std::uint8_t>{1, 0, 0});
}

TEST_CASE("build_instances: a sphere per joint, a tube per non-degenerate bone") {
  SkeletonPose a = chain();
  SkeletonPose b = chain();
  b.positions.push_back(b.positions[2]);  // zero-length bone: sphere, but no tube
  b.parents.push_back(2);
  SkeletonPose broken = chain();
  broken.parents[0] = 5;
  std::vector<glm::vec4> joints, bones;
  SkeletonRenderer::build_instances({a, b, broken}, SkeletonStyle{}, &joints, &bones);
  CHECK(joints.size() == 2 * (3 + 4));  // two vec4 per joint; `broken` is skipped
  CHECK(bones.size() == 3 * (2 + 2));   // three vec4 per bone
  // Radii follow the size: twice the size, twice the radius.
  SkeletonPose big = chain();
  for (auto& p : big.positions) p *= 2.0f;
  big.size = 4.0f;
  std::vector<glm::vec4> big_joints, big_bones;
  SkeletonRenderer::build_instances({big}, SkeletonStyle{}, &big_joints, &big_bones);
  CHECK(big_joints[0].w == Approx(2.0f * joints[0].w));
}

TEST_CASE("build_instances: a highlight recolours its joint and glows") {
  SkeletonPose pose = chain();
  pose.color = glm::vec3(1, 0, 0);
  pose.highlights.assign(3, glm::vec4(0.0f));
  pose.highlights[1] = glm::vec4(0, 1, 0, 1);
  std::vector<glm::vec4> joints, bones;
  SkeletonRenderer::build_instances({pose}, SkeletonStyle{}, &joints, &bones);
  CHECK(joints[1] == glm::vec4(1, 0, 0, 0));  // joint 0: colour, no glow
  CHECK(joints[3].g == Approx(1.0f));          // joint 1: green
  CHECK(joints[3].r == Approx(0.0f));
  CHECK(joints[3].a > 0.0f);
}
