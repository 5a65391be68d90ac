#include "engine/kinematics/convert.h"

#include <catch2/catch.hpp>
#include <string>

#include "engine/io/bvh/bvh_read.h"
#include "engine/kinematics/kinematics.h"
#include "tests/test_data.h"

using namespace mostyle;

namespace {

constexpr EulerOrder kOrders[] = {EulerOrder::kXYZ, EulerOrder::kXZY, EulerOrder::kYXZ,
                                  EulerOrder::kYZX, EulerOrder::kZXY, EulerOrder::kZYX};
constexpr double kPositionTolerance = 1e-9;  // relative to the skeleton's size

// Diagonal of the bounding box of all joints over all frames.
double skeleton_size(const Eigen::MatrixXd& positions) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (Eigen::Index j = 0; j < positions.cols() / 3; ++j) {
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], positions.col(3 * j + d).minCoeff());
      hi[d] = std::max(hi[d], positions.col(3 * j + d).maxCoeff());
    }
  }
  return (hi - lo).norm();
}

// Largest change of any rotation channel between consecutive frames, degrees.
double largest_rotation_step(const Clip& clip) {
  double worst = 0;
  for (const Joint& j : clip.skeleton.joints) {
    for (size_t c = 0; c < j.channels.size(); ++c) {
      if (!is_rotation(j.channels[c])) continue;
      const int col = j.first_channel + static_cast<int>(c);
      for (int f = 1; f < clip.frames(); ++f)
        worst = std::max(worst, std::abs(clip.motion(f, col) - clip.motion(f - 1, col)));
    }
  }
  return worst;
}

void check_conversions_keep_positions(const Clip& clip) {
  const Eigen::MatrixXd before = joint_positions(clip);
  const double size = skeleton_size(before);
  for (EulerOrder order : kOrders) {
    INFO(clip.source << " to " << euler_order_name(order));
    const Clip converted = convert_euler_order(clip, order);
    REQUIRE(converted.frames() == clip.frames());
    const Eigen::MatrixXd after = joint_positions(converted);
    CHECK((after - before).cwiseAbs().maxCoeff() <= kPositionTolerance * size);
    CHECK(largest_rotation_step(converted) <= 180.0);
    for (const Joint& j : converted.skeleton.joints) {
      EulerOrder o;
      if (!j.end_site && !j.channels.empty() && is_rotation(j.channels.back())) {
        REQUIRE(joint_euler_order(j, &o));
        CHECK(o == order);
      }
    }
  }
}

}  // namespace

TEST_CASE("joint_euler_order reads the rotation channels' order", "[convert]") {
  Joint j;
  j.channels = {Channel::kXposition, Channel::kYposition, Channel::kZposition,
                Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};
  EulerOrder o;
  REQUIRE(joint_euler_order(j, &o));
  CHECK(o == EulerOrder::kZXY);
  j.channels = {Channel::kYrotation, Channel::kXposition, Channel::kZrotation, Channel::kXrotation};
  REQUIRE(joint_euler_order(j, &o));
  CHECK(o == EulerOrder::kYZX);
  j.channels = {Channel::kXrotation, Channel::kYrotation};
  CHECK_FALSE(joint_euler_order(j, &o));
  j.channels = {};
  CHECK_FALSE(joint_euler_order(j, &o));
}

TEST_CASE("convert to each order keeps joint positions: real CMU data (assets)", "[convert]") {
  for (const std::string& path : test::asset_motions()) check_conversions_keep_positions(read_bvh_file(path));
}

TEST_CASE("convert to each order keeps joint positions: every shared file", "[convert]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  for (const std::string& path : test::shared_motions()) check_conversions_keep_positions(read_bvh_file(path));
}

TEST_CASE("convert unwraps the near-gimbal-lock CMU root: no jumps over 180 degrees", "[convert]") {
  // The CMU 142 root's middle angle (Yrotation, ZYX) comes within 5 degrees of +-90 in many
  // frames, where Z and X swing wildly; any other order must still be continuous.
  const Clip clip = read_bvh_file(test::asset("motions/cmu142_walk_happy.bvh"));
  const int hips = clip.skeleton.find("Hips");
  REQUIRE(hips == 0);
  int near_lock = 0;
  for (int f = 0; f < clip.frames(); ++f) near_lock += std::abs(std::abs(clip.motion(f, 4)) - 90) < 5;
  CHECK(near_lock > clip.frames() / 10);
  for (EulerOrder order : kOrders) {
    INFO(euler_order_name(order));
    const Clip converted = convert_euler_order(clip, order);
    for (int d = 0; d < 3; ++d) {
      for (int f = 1; f < converted.frames(); ++f)
        REQUIRE(std::abs(converted.motion(f, 3 + d) - converted.motion(f - 1, 3 + d)) <= 180.0);
    }
    // Round trip back to ZYX: same positions.
    const Clip back = convert_euler_order(converted, EulerOrder::kZYX);
    const Eigen::MatrixXd p0 = joint_positions(clip);
    CHECK((joint_positions(back) - p0).cwiseAbs().maxCoeff() <= kPositionTolerance * skeleton_size(p0));
  }
}

TEST_CASE("convert: layout is position channels first, then the three rotations", "[convert]") {
  // Mixed layouts: positions interleaved with rotations, two rotation channels, none at all.
  const std::string text =
      "HIERARCHY\nROOT Root\n{\n  OFFSET 0 0 0\n"
      "  CHANNELS 6 Yrotation Xposition Zrotation Zposition Xrotation Yposition\n"
      "  JOINT Two\n  {\n    OFFSET 0 1 0\n    CHANNELS 2 Xrotation Zrotation\n"
      "    JOINT None\n    {\n      OFFSET 0 1 0\n      CHANNELS 0\n"
      "      End Site\n      {\n        OFFSET 1 0 0\n      }\n    }\n  }\n}\n"
      "MOTION\nFrames: 2\nFrame Time: 0.01\n"
      "10 1 20 3 30 2 40 50\n-170 1.5 175 3 -30 2 40 -179\n";
  const Clip clip = parse_bvh(text, "mixed.bvh");
  const Clip converted = convert_euler_order(clip, EulerOrder::kXYZ);
  const Skeleton& s = converted.skeleton;
  CHECK(s.joints[0].channels ==
        std::vector<Channel>{Channel::kXposition, Channel::kZposition, Channel::kYposition,
                             Channel::kXrotation, Channel::kYrotation, Channel::kZrotation});
  CHECK(s.joints[1].channels ==
        std::vector<Channel>{Channel::kXrotation, Channel::kYrotation, Channel::kZrotation});
  CHECK(s.joints[2].channels.empty());
  CHECK(s.joints[1].first_channel == 6);
  CHECK(s.joints[2].first_channel == 9);
  CHECK(s.channel_count == 9);
  // Positions copied as they are, in file order.
  CHECK(converted.motion(1, 0) == 1.5);
  CHECK(converted.motion(1, 1) == 3);
  CHECK(converted.motion(1, 2) == 2);
  const Eigen::MatrixXd before = joint_positions(clip);
  CHECK((joint_positions(converted) - before).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("convert to the order a joint already has keeps its values bit for bit", "[convert]") {
  const Clip clip = read_bvh_file(test::asset("motions/cmu142_walk_joy.bvh"));
  const Clip same = convert_euler_order(clip, EulerOrder::kZYX);
  REQUIRE(same.skeleton.channel_count == clip.skeleton.channel_count);
  // Only whole-turn or other-solution changes where the file itself jumps over 180 degrees.
  int changed = 0;
  for (int f = 0; f < clip.frames(); ++f)
    for (int c = 0; c < clip.skeleton.channel_count; ++c) changed += same.motion(f, c) != clip.motion(f, c);
  const bool file_jumps = largest_rotation_step(clip) > 180.0;
  CHECK((changed == 0 || file_jumps));
  CHECK(largest_rotation_step(same) <= 180.0);
  if (!file_jumps) CHECK(same.motion == clip.motion);
}

TEST_CASE("convert of an empty clip", "[convert]") {
  const Clip clip = parse_bvh(
      "HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n"
      "End Site\n{\nOFFSET 0 1 0\n}\n}\nMOTION\nFrames: 0\nFrame Time: 0.1\n",
      "empty.bvh");
  const Clip converted = convert_euler_order(clip, EulerOrder::kXYZ);
  CHECK(converted.frames() == 0);
  CHECK(converted.motion.cols() == 3);
}
