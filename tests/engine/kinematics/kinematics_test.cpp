#include "engine/kinematics/kinematics.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "engine/io/bvh/bvh_read.h"
#include "tests/test_data.h"

using namespace mostyle;

namespace {

constexpr double kExact = 1e-12;  // hand-worked positions: only cos(90 deg) round-off

// A root at `root_offset` with the given rotation channels and one child at OFFSET (1, 2, 3),
// then an End Site. One frame: the root's values.
std::string two_joint_bvh(const std::string& root_channels, const std::string& values) {
  const int count = static_cast<int>(std::count(root_channels.begin(), root_channels.end(), ' ')) + 1;
  return "HIERARCHY\nROOT A\n{\n  OFFSET 0 0 0\n  CHANNELS " + std::to_string(count) + " " +
         root_channels +
         "\n  JOINT B\n  {\n    OFFSET 1 2 3\n    CHANNELS 0\n    End Site\n    {\n"
         "      OFFSET 0 0 1\n    }\n  }\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n" +
         values + "\n";
}

Eigen::Vector3d position(const Eigen::MatrixXd& p, int frame, int joint) {
  return p.block<1, 3>(frame, 3 * joint).transpose();
}

}  // namespace

// Rotations by 90 degrees move (x, y, z) so:
//   Rx(90): (x, -z, y)    Ry(90): (z, y, -x)    Rz(90): (-y, x, z)
// Channels "P Q R" give R = Rp * Rq * Rr (Blender's reading), applied to the child's OFFSET
// (1, 2, 3) right to left. All angles 90; the six orders give six different answers, and none
// equals the reversed product Rr * Rq * Rp.
TEST_CASE("FK of each rotation order, worked by hand", "[kinematics]") {
  struct Case {
    const char* channels;
    Eigen::Vector3d expected;
  };
  const Case cases[] = {
      // XYZ: Rz(1,2,3) = (-2,1,3); Ry -> (3,1,2); Rx -> (3,-2,1)
      {"Xrotation Yrotation Zrotation", {3, -2, 1}},
      // XZY: Ry(1,2,3) = (3,2,-1); Rz -> (-2,3,-1); Rx -> (-2,1,3)
      {"Xrotation Zrotation Yrotation", {-2, 1, 3}},
      // YXZ: Rz -> (-2,1,3); Rx -> (-2,-3,1); Ry -> (1,-3,2)
      {"Yrotation Xrotation Zrotation", {1, -3, 2}},
      // YZX: Rx(1,2,3) = (1,-3,2); Rz -> (3,1,2); Ry -> (2,1,-3)
      {"Yrotation Zrotation Xrotation", {2, 1, -3}},
      // ZXY: Ry -> (3,2,-1); Rx -> (3,1,2); Rz -> (-1,3,2)
      {"Zrotation Xrotation Yrotation", {-1, 3, 2}},
      // ZYX: Rx -> (1,-3,2); Ry -> (2,-3,-1); Rz -> (3,2,-1)
      {"Zrotation Yrotation Xrotation", {3, 2, -1}},
  };
  for (const Case& c : cases) {
    INFO(c.channels);
    const Clip clip = parse_bvh(two_joint_bvh(c.channels, "90 90 90"), "order.bvh");
    const Eigen::MatrixXd p = joint_positions(clip);
    CHECK(position(p, 0, 0).isZero(kExact));
    CHECK((position(p, 0, 1) - c.expected).norm() < kExact);
    // The End Site at (0, 0, 1) below B: B's rotation is the root's (B has no channels).
    const Eigen::Matrix3d r = pose_at(clip, 0).rotations[0];
    CHECK((position(p, 0, 2) - (c.expected + r * Eigen::Vector3d(0, 0, 1))).norm() < kExact);
  }
}

TEST_CASE("FK takes each rotation value from its own channel", "[kinematics]") {
  // Only the middle channel non-zero: for "Zrotation Xrotation Yrotation" that is Rx(90):
  // (1,2,3) -> (1,-3,2). Only the last: Ry(90): (3,2,-1).
  Clip clip = parse_bvh(two_joint_bvh("Zrotation Xrotation Yrotation", "0 90 0"), "x.bvh");
  CHECK((position(joint_positions(clip), 0, 1) - Eigen::Vector3d(1, -3, 2)).norm() < kExact);
  clip = parse_bvh(two_joint_bvh("Zrotation Xrotation Yrotation", "0 0 90"), "y.bvh");
  CHECK((position(joint_positions(clip), 0, 1) - Eigen::Vector3d(3, 2, -1)).norm() < kExact);
  // One or two rotation channels: the product of those present, in file order.
  // Yrotation 90, Xrotation 90: Ry * Rx: Rx(1,2,3) = (1,-3,2); Ry -> (2,-3,-1).
  clip = parse_bvh(two_joint_bvh("Yrotation Xrotation", "90 90"), "yx.bvh");
  CHECK((position(joint_positions(clip), 0, 1) - Eigen::Vector3d(2, -3, -1)).norm() < kExact);
}

TEST_CASE("FK of 6-channel joints: position channels replace the OFFSET", "[kinematics]") {
  // Bandai's layout: every joint has 6 channels. The root sits at (10, 20, 30) turned by
  // Rz(90); the child's position channels (1, 0, 0) replace its OFFSET (100, 100, 100), so it is
  // at (10, 20, 30) + Rz(90)(1, 0, 0) = (10, 21, 30). Its own Rx(90) then turns its End Site
  // (0, 1, 0): global rotation Rz(90) Rx(90) maps (0,1,0) -> Rx: (0,0,1) -> Rz: (0,0,1), so the
  // End Site is at (10, 21, 31). Position channels in any order: "Zposition Xposition Yposition".
  const std::string text =
      "HIERARCHY\nROOT Root\n{\n  OFFSET 5 5 5\n"
      "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
      "  JOINT Child\n  {\n    OFFSET 100 100 100\n"
      "    CHANNELS 6 Zposition Xposition Yposition Zrotation Xrotation Yrotation\n"
      "    End Site\n    {\n      OFFSET 0 1 0\n    }\n  }\n}\n"
      "MOTION\nFrames: 1\nFrame Time: 0.0333333\n"
      "10 20 30 90 0 0  0 1 0 0 90 0\n";
  const Clip clip = parse_bvh(text, "six.bvh");
  const Eigen::MatrixXd p = joint_positions(clip);
  CHECK((position(p, 0, 0) - Eigen::Vector3d(10, 20, 30)).norm() < kExact);
  CHECK((position(p, 0, 1) - Eigen::Vector3d(10, 21, 30)).norm() < kExact);
  CHECK((position(p, 0, 2) - Eigen::Vector3d(10, 21, 31)).norm() < kExact);
}

TEST_CASE("FK: one position channel replaces the whole OFFSET, as in Blender", "[kinematics]") {
  // Blender's importer places a joint with any location channel at (lx, ly, lz), unset ones 0,
  // whatever its OFFSET (checked against Blender 3.4's io_anim_bvh). OFFSET (15, 5, 7),
  // Yposition 2: the child is at (0, 2, 0).
  const std::string text =
      "HIERARCHY\nROOT Root\n{\n  OFFSET 0 0 0\n  CHANNELS 0\n"
      "  JOINT Arm\n  {\n    OFFSET 15 5 7\n    CHANNELS 1 Yposition\n"
      "    End Site\n    {\n      OFFSET 1 0 0\n    }\n  }\n}\n"
      "MOTION\nFrames: 1\nFrame Time: 0.0333333\n2\n";
  const Clip clip = parse_bvh(text, "partial.bvh");
  const Eigen::MatrixXd p = joint_positions(clip);
  CHECK((position(p, 0, 1) - Eigen::Vector3d(0, 2, 0)).norm() < kExact);
  CHECK((position(p, 0, 2) - Eigen::Vector3d(1, 2, 0)).norm() < kExact);
  const double values[] = {2.0};
  CHECK(joint_local_translation(clip.skeleton.joints[1], values) == Eigen::Vector3d(0, 2, 0));
  CHECK(joint_local_translation(clip.skeleton.joints[2], values) == Eigen::Vector3d(1, 0, 0));
}

TEST_CASE("joint_positions, pose_at and rest_positions agree", "[kinematics]") {
  const Clip clip = read_bvh_file(test::asset_motions().front());
  const Eigen::MatrixXd p = joint_positions(clip);
  REQUIRE(p.rows() == clip.frames());
  REQUIRE(p.cols() == 3 * static_cast<int>(clip.skeleton.joints.size()));
  for (int f : {0, clip.frames() / 2, clip.frames() - 1}) {
    const Pose pose = pose_at(clip, f);
    for (size_t j = 0; j < clip.skeleton.joints.size(); ++j) {
      CHECK((pose.positions[j] - position(p, f, static_cast<int>(j))).norm() == 0.0);
      // Global rotations are rotations.
      CHECK((pose.rotations[j] * pose.rotations[j].transpose() - Eigen::Matrix3d::Identity())
                .norm() < 1e-12);
    }
  }
  // The rest pose chains the OFFSETs.
  const std::vector<Eigen::Vector3d> rest = rest_positions(clip.skeleton);
  for (size_t j = 0; j < rest.size(); ++j) {
    const Joint& joint = clip.skeleton.joints[j];
    const Eigen::Vector3d expected =
        joint.parent < 0 ? joint.offset : Eigen::Vector3d(rest[joint.parent] + joint.offset);
    CHECK((rest[j] - expected).norm() == 0.0);
  }
}

TEST_CASE("FK of some joints poses them exactly as FK of all", "[kinematics]") {
  const Clip clip = read_bvh_file(test::asset_motions().front());
  const Eigen::MatrixXd all = joint_positions(clip);
  const int last = static_cast<int>(clip.skeleton.joints.size()) - 1;
  const std::vector<int> joints = {last, 0, last / 2, last / 2};  // any order, repeats allowed
  const Eigen::MatrixXd some = joint_positions(clip, joints);
  REQUIRE(some.rows() == clip.frames());
  REQUIRE(some.cols() == 3 * static_cast<Eigen::Index>(joints.size()));
  for (size_t i = 0; i < joints.size(); ++i)
    CHECK(some.middleCols(3 * static_cast<Eigen::Index>(i), 3) == all.middleCols(3 * joints[i], 3));
  CHECK(joint_positions(clip, {}).cols() == 0);
}

TEST_CASE("one frame's FK poses real takes' frames exactly as the whole clip's FK", "[kinematics]") {
  for (const std::string& path : test::asset_motions()) {
    INFO(path);
    const Clip clip = read_bvh_file(path);
    const int n = static_cast<int>(clip.skeleton.joints.size());
    std::vector<int> every(static_cast<size_t>(n));
    for (int j = 0; j < n; ++j) every[static_cast<size_t>(j)] = j;
    // The four-frame FK of joint_positions(clip, joints) is code of its own: the same values.
    const Eigen::MatrixXd whole = joint_positions(clip, every);
    // A leg's chain only: the hips' descendants down one side, with their ancestors.
    std::vector<int> chain;
    for (int j = 0; j < n && chain.size() < 5; ++j)
      if (j == 0 || clip.skeleton.joints[static_cast<size_t>(j)].parent == chain.back()) chain.push_back(j);
    Pose pose, part;
    part.rotations.assign(static_cast<size_t>(n), Eigen::Matrix3d::Identity());
    part.positions.assign(static_cast<size_t>(n), Eigen::Vector3d::Zero());
    for (int f = 0; f < clip.frames(); ++f) {
      const double* row = clip.motion.row(f).data();
      pose_frame(clip.skeleton, row, &pose);
      REQUIRE(pose.positions.size() == static_cast<size_t>(n));
      bool same = true;
      for (int j = 0; j < n; ++j) same = same && pose.positions[static_cast<size_t>(j)] == position(whole, f, j);
      pose_frame(clip.skeleton, row, chain, &part);
      for (int j : chain)
        same = same && part.positions[static_cast<size_t>(j)] == pose.positions[static_cast<size_t>(j)] &&
               part.rotations[static_cast<size_t>(j)] == pose.rotations[static_cast<size_t>(j)];
      if (!same) FAIL("frame " << f << " differs");
    }
    // Joints off the chain are left as they were.
    CHECK(part.positions[static_cast<size_t>(n - 1)] == Eigen::Vector3d::Zero());
  }
}

TEST_CASE("rest_positions turns each OFFSET by its parents' rest rotations", "[kinematics]") {
  // An FBX or glTF rest pose: the root turned a quarter about Z, the arm a quarter about Y.
  Skeleton s;
  Joint root, arm, hand;
  root.name = "root";
  root.offset = Eigen::Vector3d(5, 0, 0);
  root.rest_rotation = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  arm.name = "arm";
  arm.parent = 0;
  arm.offset = Eigen::Vector3d(2, 0, 0);
  arm.rest_rotation = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  hand.name = "hand";
  hand.parent = 1;
  hand.offset = Eigen::Vector3d(1, 0, 0);
  s.joints = {root, arm, hand};
  const std::vector<Eigen::Vector3d> rest = rest_positions(s);
  // arm: the root's turn takes +X to +Y; hand: Rz(90) Ry(90) takes +X to Rz(90) (0, 0, -1) = (0, 0, -1).
  CHECK((rest[1] - Eigen::Vector3d(5, 2, 0)).norm() < 1e-12);
  CHECK((rest[2] - Eigen::Vector3d(5, 2, -1)).norm() < 1e-12);
}

TEST_CASE("FK keeps bone lengths: real CMU files (assets)", "[kinematics]") {
  for (const std::string& path : test::asset_motions()) {
    INFO(path);
    const Clip clip = read_bvh_file(path);
    const Eigen::MatrixXd p = joint_positions(clip);
    const Skeleton& s = clip.skeleton;
    for (size_t j = 1; j < s.joints.size(); ++j) {
      const double length = s.joints[j].offset.norm();  // CMU: no position channels below root
      for (int f = 0; f < clip.frames(); f += 97) {
        const double d = (position(p, f, static_cast<int>(j)) - position(p, f, s.joints[j].parent)).norm();
        CHECK(d == Approx(length).margin(1e-9));
      }
    }
    // CMU 142: Hips about 17 units up (README), standing at the start.
    CHECK(p(0, 1) == Approx(17).margin(2));
  }
}

TEST_CASE("FK of real Bandai files: channels replace offsets, bones keep their length",
          "[kinematics]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  for (const std::string& name : {"bandai_walk_normal.bvh", "bandai_walk_old.bvh"}) {
    INFO(name);
    const Clip clip = read_bvh_file(test::shared_motion(name));
    const Eigen::MatrixXd p = joint_positions(clip);
    const Skeleton& s = clip.skeleton;
    const int hips = s.find("Hips");
    const int spine = s.find("Spine");
    REQUIRE(hips > 0);
    // The trajectory is on Hips (Y about 90), not the static ROOT; adding OFFSET (0, 93.9, -3)
    // or (0.8, 94, -452) to the channels would lift it to about 184 or move it 4.5 m.
    for (int f = 0; f < clip.frames(); f += 10) {
      CHECK(position(p, f, 0).isZero());
      CHECK(p(f, 3 * hips + 1) == Approx(90).margin(8));
      // Non-root position channels equal the OFFSET (README oddity 1): Spine is its OFFSET's
      // length (15.7357) from Hips; adding would double it.
      CHECK((position(p, f, spine) - position(p, f, hips)).norm() ==
            Approx(s.joints[spine].offset.norm()).epsilon(1e-5));
    }
  }
}

TEST_CASE("FK handles a 20000-deep hierarchy without recursion", "[kinematics]") {
  constexpr int kDepth = 20000;
  std::string text = "HIERARCHY\n";
  for (int i = 0; i < kDepth; ++i)
    text += (i ? "JOINT j" : "ROOT j") + std::to_string(i) + "\n{\nOFFSET 0 1 0\nCHANNELS 1 Zrotation\n";
  text += "End Site\n{\nOFFSET 0 1 0\n}\n";
  for (int i = 0; i < kDepth; ++i) text += "}\n";
  text += "MOTION\nFrames: 1\nFrame Time: 1\n";
  for (int i = 0; i < kDepth; ++i) text += i ? " 0" : "0";
  text += "\n";
  const Clip clip = parse_bvh(text, "deep.bvh");
  const Eigen::MatrixXd p = joint_positions(clip);
  // A straight chain up +Y: joint i at height i + 1, the End Site at kDepth + 1.
  CHECK(p(0, 3 * (kDepth - 1) + 1) == kDepth);
  CHECK(p(0, 3 * kDepth + 1) == kDepth + 1);
}

TEST_CASE("chain_joints: the joints asked for and their ancestors, once each, parents first") {
  const Clip clip = parse_bvh(
      "HIERARCHY\nROOT R\n{\nOFFSET 0 0 0\nCHANNELS 3 Xposition Yposition Zposition\n"
      "JOINT A\n{\nOFFSET 1 0 0\nCHANNELS 0\nJOINT B\n{\nOFFSET 1 0 0\nCHANNELS 0\nEnd Site\n{\nOFFSET 1 0 0\n}\n}\n}\n"
      "JOINT C\n{\nOFFSET 0 1 0\nCHANNELS 0\nEnd Site\n{\nOFFSET 0 1 0\n}\n}\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n0 0 0\n",
      "chain.bvh");
  // Joints in file order: R 0, A 1, B 2, B's end 3, C 4, C's end 5.
  CHECK(chain_joints(clip.skeleton, {2}) == std::vector<int>{0, 1, 2});
  CHECK(chain_joints(clip.skeleton, {4, 2, 1}) == std::vector<int>{0, 1, 2, 4});
  CHECK(chain_joints(clip.skeleton, {}).empty());
}
