#include "engine/prepare/rig_structure.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "engine/io/motion_file.h"
#include "tests/engine/skeleton_builder.h"
#include "tests/test_data.h"

using namespace mostyle;
using Catch::Matchers::Contains;

namespace {

constexpr int kHips = static_cast<int>(MajorJoint::kHips);
constexpr int kLeftHip = static_cast<int>(MajorJoint::kLeftHip);
constexpr int kLeftKnee = static_cast<int>(MajorJoint::kLeftKnee);
constexpr int kLeftAnkle = static_cast<int>(MajorJoint::kLeftAnkle);
constexpr int kLeftToe = static_cast<int>(MajorJoint::kLeftToe);
constexpr int kRightAnkle = static_cast<int>(MajorJoint::kRightAnkle);
constexpr int kLeftShoulder = static_cast<int>(MajorJoint::kLeftShoulder);
constexpr int kLeftHand = static_cast<int>(MajorJoint::kLeftHand);
constexpr int kRightHand = static_cast<int>(MajorJoint::kRightHand);

// The same skeleton with every joint called j0, j1, ... (its index): only its shape is left.
Skeleton unnamed(Skeleton s) {
  for (size_t i = 0; i < s.joints.size(); ++i)
    s.joints[i].name = "j" + std::to_string(i) + (s.joints[i].end_site ? " End Site" : "");
  return s;
}

// The same skeleton without its End Sites, as FBX and glTF files have it: a leaf joint there
// ends nowhere.
Skeleton without_end_sites(const Skeleton& s) {
  Skeleton out;
  std::vector<int> index(s.joints.size(), -1);
  for (size_t i = 0; i < s.joints.size(); ++i) {
    if (s.joints[i].end_site) continue;
    Joint j = s.joints[i];
    j.parent = j.parent < 0 ? -1 : index[static_cast<size_t>(j.parent)];
    j.first_channel = out.channel_count;
    out.channel_count += static_cast<int>(j.channels.size());
    index[i] = static_cast<int>(out.joints.size());
    out.joints.push_back(j);
  }
  return out;
}

// Every offset (and so the rest pose) taken through m.
Skeleton transformed(Skeleton s, const Eigen::Matrix3d& m) {
  for (Joint& j : s.joints) j.offset = m * j.offset;
  return s;
}

// The joint of `name` in the (named) skeleton the structure's indices refer to.
int joint(const Skeleton& named, const std::string& name) {
  const int j = named.find(name);
  REQUIRE(j >= 0);
  return j;
}

// A rig with no names: hips 95 high, thighs 9 to the side, shins 42 and 42 long, the knees
// `knee_forward` ahead of the hip-ankle line, feet ending in an End Site `foot` from the ankle;
// a spine, a head and arms. Left (+X) joints are j2.. and right (-X) j5..: see the indices.
Skeleton plain_rig(double knee_forward, const Eigen::Vector3d& foot) {
  test::SkeletonBuilder b;
  b.joint("j0", "", 0, 95, 0);                                   // 0 hips
  b.joint("j1", "j0", 9, -5, 0)                                  // 1 left thigh
      .joint("j2", "j1", 0, -42, knee_forward)                   // 2 left knee
      .joint("j3", "j2", 0, -42, -knee_forward)                  // 3 left ankle
      .end("j3", foot.x(), foot.y(), foot.z());
  b.joint("j4", "j0", -9, -5, 0)                                 // 5 right thigh (4 is the End Site)
      .joint("j5", "j4", 0, -42, knee_forward)                   // 6 right knee
      .joint("j6", "j5", 0, -42, -knee_forward)                  // 7 right ankle
      .end("j6", foot.x(), foot.y(), foot.z());
  b.joint("j7", "j0", 0, 12, 0)                                  // 9 spine
      .joint("j8", "j7", 0, 15, 0)                               // 10 chest
      .joint("j9", "j8", 0, 25, 0)                               // 11 head
      .end("j9", 0, 15, 0);
  for (double sign : {1.0, -1.0}) {
    const std::string s = sign > 0 ? "l" : "r";
    b.joint("a" + s, "j8", sign * 18, 15, 0)
        .joint("b" + s, "a" + s, sign * 28, 0, 0)
        .joint("c" + s, "b" + s, sign * 25, 0, 0)
        .end("c" + s, sign * 8, 0, 0);
  }
  return b.skeleton();
}

}  // namespace

TEST_CASE("structure: unnamed rigs of the common conventions map as their names do", "[rig_structure]") {
  struct Case {
    const char* what;
    Skeleton skeleton;
  };
  const std::vector<Case> cases = {{"CMU", test::cmu_retargeted_skeleton()},
                                   {"Bandai", test::bandai_skeleton()},
                                   {"Kinect", test::kinect_skeleton()},
                                   {"Poser", test::cmu_poser_skeleton()},
                                   {"no toes, no hands", test::no_toes_no_hands_skeleton()}};
  for (const Case& c : cases) {
    INFO(c.what);
    const MajorMapping by_name = map_major_joints(c.skeleton);
    const RigStructure structure = find_rig_structure(unnamed(c.skeleton));
    INFO(structure.summary);
    for (int major = 0; major < kMajorJointCount; ++major) {
      INFO(major_joint_name(major));
      CHECK(structure.joint[major] == by_name.joint[major]);
    }
    CHECK(structure.facing == FacingCue::kRestToes);
    // Through map_major_joints: every joint found is the structure's.
    const MajorMapping m = map_major_joints(unnamed(c.skeleton));
    for (int major = 0; major < kMajorJointCount; ++major) {
      CHECK(m.joint[major] == by_name.joint[major]);
      if (m.has(major)) CHECK(m.source[major] == MajorSource::kStructure);
    }
    CHECK_THAT(m.how, Contains("by structure") && Contains("left told by the toes in the rest pose"));
  }
}

TEST_CASE("structure: end markers are no head, and a hand goes on along the forearm", "[rig_structure]") {
  // Mixamo's FBX and glTF files keep HeadTop_End and Toe_End leaves (no End Site) that never
  // move: with a motion that moves nothing but the root, every leaf is such a marker, and the
  // head is Head.
  const Skeleton s = without_end_sites(test::mixamo_skeleton());
  const Clip still = test::still_clip(s, 10, 1.0);
  const RigStructure r = find_rig_structure(unnamed(s), &still.motion);
  const MajorMapping by_name = map_major_joints(s);
  for (int major = 0; major < kMajorJointCount; ++major) {
    if (major == kLeftHand || major == kRightHand) continue;  // five like fingers: see below
    INFO(major_joint_name(major));
    CHECK(r.joint[major] == by_name.joint[major]);
  }
  // Without the motion nothing is known to be a marker: the head is the chain's last joint; in a
  // BVH the End Site is the marker, and a leaf joint is a joint even when it does not move.
  CHECK(find_rig_structure(unnamed(s)).joint[static_cast<int>(MajorJoint::kHead)] ==
        joint(s, "mixamorig:HeadTop_End"));
  const Skeleton bvh = test::mixamo_skeleton();
  const Clip still_bvh = test::still_clip(bvh, 10, 1.0);
  CHECK(find_rig_structure(unnamed(bvh), &still_bvh.motion).joint[static_cast<int>(MajorJoint::kHead)] ==
        joint(bvh, "mixamorig:HeadTop_End"));
  // A thumb off to the side and a middle finger straight on: the hand is the middle finger's.
  test::SkeletonBuilder b;
  b.joint("j0", "", 0, 95, 0);
  for (double sign : {1.0, -1.0}) {
    const std::string s2 = sign > 0 ? "l" : "r";
    b.joint("t" + s2, "j0", sign * 9, -5, 0).joint("k" + s2, "t" + s2, 0, -42, 0).joint("f" + s2, "k" + s2, 0, -42, 0);
    b.end("f" + s2, 0, -6, 13);
  }
  b.joint("s", "j0", 0, 27, 0).joint("h", "s", 0, 25, 0).end("h", 0, 15, 0);
  for (double sign : {1.0, -1.0}) {
    const std::string s2 = sign > 0 ? "l" : "r";
    b.joint("u" + s2, "s", sign * 18, 15, 0)
        .joint("e" + s2, "u" + s2, sign * 28, 0, 0)
        .joint("w" + s2, "e" + s2, sign * 25, 0, 0)
        .joint("thumb" + s2, "w" + s2, sign * 3, 0, 4)
        .joint("thumb2" + s2, "thumb" + s2, sign * 3, 0, 2)
        .joint("middle" + s2, "w" + s2, sign * 9, 0, 0)
        .joint("middle2" + s2, "middle" + s2, sign * 3, 0, 0);
  }
  const RigStructure hands = find_rig_structure(b.skeleton());
  CHECK(hands.joint[kLeftHand] == joint(b.skeleton(), "middlel"));
  CHECK(hands.joint[kRightHand] == joint(b.skeleton(), "middler"));
}

TEST_CASE("structure: left and right from the facing, turned or mirrored", "[rig_structure]") {
  const Skeleton cmu = test::cmu_retargeted_skeleton();
  SECTION("turned half round: facing -Z, the left side is -X, the same joints") {
    const Skeleton turned = transformed(cmu, Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()).toRotationMatrix());
    const RigStructure r = find_rig_structure(unnamed(turned));
    CHECK(r.joint[kLeftHip] == joint(cmu, "LeftUpLeg"));
    CHECK(r.joint[kLeftShoulder] == joint(cmu, "LeftArm"));
    CHECK(r.facing == FacingCue::kRestToes);
    // Its names agree with its body: kept.
    const MajorMapping m = map_major_joints(turned);
    CHECK(m.joint[kLeftHip] == joint(cmu, "LeftUpLeg"));
    CHECK(m.how.find("swapped") == std::string::npos);
  }
  SECTION("mirrored: the joints named left lie on the body's right") {
    const Eigen::Matrix3d mirror = Eigen::Vector3d(-1, 1, 1).asDiagonal();
    const Skeleton mirrored = transformed(cmu, mirror);
    const RigStructure r = find_rig_structure(unnamed(mirrored));
    CHECK(r.joint[kLeftHip] == joint(cmu, "RightUpLeg"));
    CHECK(r.joint[kLeftAnkle] == joint(cmu, "RightFoot"));
    CHECK(r.joint[kLeftShoulder] == joint(cmu, "RightArm"));
    CHECK(r.joint[kRightAnkle] == joint(cmu, "LeftFoot"));
    // With its names: they are told to disagree, and the body's sides win for every joint.
    MajorMapping names;
    names.joint[kLeftHip] = joint(cmu, "LeftUpLeg");
    CHECK(find_rig_structure(mirrored, nullptr, &names).names_sides == -1);
    CHECK(find_rig_structure(cmu, nullptr, &names).names_sides == 1);
    const MajorMapping m = map_major_joints(mirrored);
    CHECK(m.joint[kLeftHip] == joint(cmu, "RightUpLeg"));
    CHECK(m.joint[kLeftHand] == joint(cmu, "RightHandIndex1"));
    CHECK(m.source[kLeftHip] == MajorSource::kName);
    CHECK_THAT(m.how, Contains("the names' left and right are swapped") && Contains("the toes in the rest pose"));
  }
}

TEST_CASE("structure: the facing from the knees, the motion, the root's travel", "[rig_structure]") {
  const Eigen::Vector3d down(0, -6, 0);  // feet that point nowhere
  SECTION("knees bent forward (+Z) in the rest pose") {
    const RigStructure r = find_rig_structure(plain_rig(6, down));
    CHECK(r.facing == FacingCue::kRestKnees);
    CHECK(r.joint[kLeftHip] == 1);
    CHECK(r.joint[kLeftKnee] == 2);
    CHECK(r.joint[kLeftAnkle] == 3);
    CHECK(r.joint[kLeftToe] == -1);  // an End Site is no toe
  }
  SECTION("knees bent towards -Z: that is forward, and -X is left") {
    const RigStructure r = find_rig_structure(plain_rig(-6, down));
    CHECK(r.facing == FacingCue::kRestKnees);
    CHECK(r.joint[kLeftHip] == 5);
    CHECK(r.joint[kLeftShoulder] == 17);
  }
  // Straight legs and feet that point nowhere: the rest pose cannot tell.
  const Skeleton straight = plain_rig(0, down);
  SECTION("nothing tells: +Z is taken, and the sentence says so") {
    const RigStructure r = find_rig_structure(straight);
    CHECK(r.facing == FacingCue::kNone);
    CHECK(r.joint[kLeftHip] == 1);
    CHECK_THAT(r.summary, Contains("+Z is taken as the facing"));
  }
  // Thighs raised 30 degrees and shins bent back 60 about X: the knees ahead of the line from hip
  // to ankle, towards +Z (or -Z with the angles' signs turned).
  const auto bent = [&](double sign) {
    Clip clip = test::still_clip(straight, 20, 0.0);
    for (const char* thigh : {"j1", "j4"}) {
      const Joint& t = straight.joints[straight.find(thigh)];
      const Joint& k = straight.joints[straight.find(thigh == std::string("j1") ? "j2" : "j5")];
      clip.motion.col(t.first_channel + 1).setConstant(-30.0 * sign);  // Xrotation (ZXY)
      clip.motion.col(k.first_channel + 1).setConstant(60.0 * sign);
    }
    return clip;
  };
  SECTION("the knees' bend over the motion") {
    const Clip forward = bent(1.0);
    RigStructure r = find_rig_structure(straight, &forward.motion);
    CHECK(r.facing == FacingCue::kMotionKnees);
    CHECK(r.joint[kLeftHip] == 1);
    const Clip backward = bent(-1.0);
    r = find_rig_structure(straight, &backward.motion);
    CHECK(r.facing == FacingCue::kMotionKnees);
    CHECK(r.joint[kLeftHip] == 5);
    // map_major_joints reads the clip's motion the same way.
    CHECK(map_major_joints(backward).joint[kLeftHip] == 5);
  }
  SECTION("the root's travel") {
    const Clip walk = test::still_clip(straight, 60, -1.0);  // along -Z
    const RigStructure r = find_rig_structure(straight, &walk.motion);
    CHECK(r.facing == FacingCue::kTravel);
    CHECK(r.joint[kLeftHip] == 5);
    CHECK_THAT(r.summary, Contains("left told by the root's travel"));
  }
}

TEST_CASE("structure: an IK rig's ankle hangs from the root, at the shin's end", "[rig_structure]") {
  for (bool end_site : {true, false}) {
    INFO((end_site ? "the shin ends in an End Site" : "the shin is a leaf joint"));
    test::SkeletonBuilder b;
    b.joint("root", "", 0, 0, 0).joint("j0", "root", 0, 95, 0);
    for (double sign : {1.0, -1.0}) {
      const std::string s = sign > 0 ? "a" : "b";
      b.joint(s + "1", "j0", sign * 9, -5, 0).joint(s + "2", s + "1", 0, -42, 0);
      if (end_site) b.end(s + "2", 0, -42, 0);
      // The foot the IK solver places: under the root, at the ankle, with its toe.
      b.joint(s + "ik", "root", sign * 9, 6, 0).joint(s + "toe", s + "ik", 0, -6, 13).end(s + "toe", 0, 0, 3);
    }
    b.joint("s", "j0", 0, 27, 0).joint("h", "s", 0, 25, 0).end("h", 0, 15, 0);
    for (double sign : {1.0, -1.0}) {
      const std::string s = sign > 0 ? "l" : "r";
      b.joint("u" + s, "s", sign * 18, 15, 0).joint("e" + s, "u" + s, sign * 28, 0, 0).joint("w" + s, "e" + s, sign * 25, 0, 0);
    }
    const Skeleton& k = b.skeleton();
    const RigStructure r = find_rig_structure(k);
    INFO(r.summary);
    CHECK(r.joint[kHips] == joint(k, "j0"));
    CHECK(r.joint[kLeftHip] == joint(k, "a1"));
    CHECK(r.joint[kLeftKnee] == joint(k, "a2"));
    CHECK(r.joint[kLeftAnkle] == joint(k, "aik"));
    CHECK(r.joint[kLeftToe] == joint(k, "atoe"));
    CHECK(r.joint[kRightAnkle] == joint(k, "bik"));
    CHECK(r.facing == FacingCue::kRestToes);  // the IK feet's toes point +Z
    CHECK_THAT(r.summary, Contains("an ankle from the joint at the shin's end"));
    // The name rules take no "root" on the floor for the hips: the structure's are the hips.
    const MajorMapping m = map_major_joints(k);
    CHECK(m.joint[kHips] == joint(k, "j0"));
    CHECK(m.source[kHips] == MajorSource::kStructure);
    CHECK(m.joint[kLeftAnkle] == joint(k, "aik"));
  }
}

TEST_CASE("structure: what cannot be read is one sentence of what was found and what is missing",
          "[rig_structure]") {
  SECTION("a chain: no legs") {
    test::SkeletonBuilder b;
    b.joint("a", "", 0, 100, 0).joint("b", "a", 0, -30, 0).joint("c", "b", 0, -30, 0).end("c", 0, -30, 0);
    const RigStructure r = find_rig_structure(b.skeleton());
    for (int j : r.joint) CHECK(j == -1);
    CHECK_THAT(r.summary, Contains("no legs"));
    const MajorMapping m = map_major_joints(b.skeleton());
    CHECK_THAT(m.how, Contains("structure: no legs"));
  }
  SECTION("legs and a spine but no arms") {
    test::SkeletonBuilder b;
    b.joint("p", "", 0, 95, 0);
    for (double sign : {1.0, -1.0}) {
      const std::string s = sign > 0 ? "l" : "r";
      b.joint("t" + s, "p", sign * 9, -5, 0).joint("k" + s, "t" + s, 0, -42, 0).joint("f" + s, "k" + s, 0, -42, 0)
          .joint("o" + s, "f" + s, 0, -6, 13);
    }
    b.joint("s", "p", 0, 27, 0).joint("h", "s", 0, 25, 0);
    const RigStructure r = find_rig_structure(b.skeleton());
    CHECK(r.joint[kLeftAnkle] == joint(b.skeleton(), "fl"));
    CHECK(r.joint[kLeftShoulder] == -1);
    CHECK_THAT(r.summary, Contains("hips 'p' with two legs") && Contains("not found: arms"));
  }
}

namespace {

// A robot as game characters are drawn: the hips at 22 of its 100 units (short legs, 9 and 9),
// a tall torso and head, and long arms hanging by its sides down to 23, whose forearms end in a
// palm and a thumb. Joints named as in a Blender rig.
Skeleton robot_rig() {
  test::SkeletonBuilder b;
  b.joint("Hips", "", 0, 22, 0);
  for (double sign : {-1.0, 1.0}) {
    const std::string s = sign > 0 ? ".L" : ".R";
    b.joint("UpperLeg" + s, "Hips", sign * 8, -2, 0)
        .joint("LowerLeg" + s, "UpperLeg" + s, 0, -9, 0)
        .joint("Foot" + s, "LowerLeg" + s, 0, -9, 0)
        .end("Foot" + s, 0, -2, 5);
  }
  b.joint("Abdomen", "Hips", 0, 8, 0).joint("Torso", "Abdomen", 0, 15, 0);
  b.joint("Neck", "Torso", 0, 20, 0).joint("Head", "Neck", 0, 5, 0).end("Head", 0, 30, 0);
  for (double sign : {-1.0, 1.0}) {
    const std::string s = sign > 0 ? ".L" : ".R";
    b.joint("Shoulder" + s, "Torso", sign * 15, 15, 0)
        .joint("UpperArm" + s, "Shoulder" + s, sign * 5, 0, 0)
        .joint("LowerArm" + s, "UpperArm" + s, 0, -15, 0)
        .joint("Palm" + s, "LowerArm" + s, 0, -12, 0)
        .end("Palm" + s, 0, -10, 0);
    b.joint("Thumb" + s, "LowerArm" + s, -sign * 3, -6, 3).end("Thumb" + s, 0, -8, 0);
  }
  return b.skeleton();
}

// A cartoon: a head half its height, legs of 12 (the hips at 13), a tail from the hips that lies
// on the floor behind it, and stubby arms.
Skeleton cartoon_rig() {
  test::SkeletonBuilder b;
  b.joint("root", "", 0, 13, 0);
  for (double sign : {1.0, -1.0}) {
    const std::string s = sign > 0 ? "_l" : "_r";
    b.joint("thigh" + s, "root", sign * 6, -1, 0)
        .joint("shin" + s, "thigh" + s, 0, -6, 1)
        .joint("ankle" + s, "shin" + s, 0, -6, -1)
        .end("ankle" + s, 0, 0, 6);
  }
  b.joint("tail1", "root", 0, -4, -8).joint("tail2", "tail1", 0, -6, -8).joint("tail3", "tail2", 0, -3, -8);
  b.joint("belly", "root", 0, 10, 0).joint("chest", "belly", 0, 12, 0);
  b.joint("head", "chest", 0, 10, 0).end("head", 0, 55, 0);
  for (double sign : {1.0, -1.0}) {
    const std::string s = sign > 0 ? "_l" : "_r";
    b.joint("arm" + s, "chest", sign * 10, 2, 0).joint("elbow" + s, "arm" + s, sign * 6, -4, 0)
        .joint("hand" + s, "elbow" + s, sign * 6, -4, 0).end("hand" + s, sign * 3, -2, 0);
  }
  return b.skeleton();
}

}  // namespace

TEST_CASE("structure: the hips of a robot and a cartoon, whose legs are short and whose arms or tail hang low",
          "[rig_structure]") {
  SECTION("a robot: long arms whose forearms branch downwards are no legs") {
    const Skeleton k = robot_rig();
    const RigStructure r = find_rig_structure(k);
    INFO(r.summary);
    CHECK(r.joint[kHips] == joint(k, "Hips"));
    CHECK(r.joint[kLeftHip] == joint(k, "UpperLeg.L"));
    CHECK(r.joint[kLeftKnee] == joint(k, "LowerLeg.L"));
    CHECK(r.joint[kLeftAnkle] == joint(k, "Foot.L"));
    CHECK(r.joint[kRightAnkle] == joint(k, "Foot.R"));
    CHECK(r.joint[kLeftShoulder] == joint(k, "UpperArm.L"));
    CHECK(r.joint[static_cast<int>(MajorJoint::kHead)] == joint(k, "Head"));
    const RigStructure bare = find_rig_structure(unnamed(k));
    CHECK(bare.joint[kHips] == joint(k, "Hips"));
  }
  SECTION("a cartoon: the tail on the floor is no leg") {
    const Skeleton k = cartoon_rig();
    const RigStructure r = find_rig_structure(k);
    INFO(r.summary);
    CHECK(r.joint[kHips] == joint(k, "root"));
    CHECK(r.joint[kLeftHip] == joint(k, "thigh_l"));
    CHECK(r.joint[kLeftAnkle] == joint(k, "ankle_l"));
    CHECK(r.joint[kRightAnkle] == joint(k, "ankle_r"));
    CHECK(r.joint[static_cast<int>(MajorJoint::kHead)] == joint(k, "head"));
  }
}

TEST_CASE("structure: the hips of every rig in shared/motions, by structure alone", "[rig_structure][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  // The joint the legs and the spine branch from, read off each rig's hierarchy by hand.
  const std::map<std::string, std::string> hips_of = {
      {"fbx_mixamo_walking.fbx", "mixamorig:Hips"},
      {"gltf_cesiumman_walk.glb", "Skeleton_torso_joint_1"},
      {"gltf_godot_mixamo_walk_run.glb", "mixamorig:Hips"},
      {"gltf_godot_robot_walk_run.glb", "hip"},
      {"gltf_mannequiny_run.glb", "pelvis"},
  };
  int rigs = 0;
  for (const char* folder : {"", "actions", "formats", "wild"}) {
    const std::string dir = test::shared_motion(folder);
    if (dir.empty()) continue;
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
      if (is_motion_file(entry.path().string())) files.push_back(entry.path().string());
    std::sort(files.begin(), files.end());
    for (const std::string& file : files) {
      INFO(file);
      const Clip clip = read_motion_file(file);
      const RigStructure r = find_rig_structure(unnamed(clip.skeleton), &clip.motion);
      INFO(r.summary);
      const auto known = hips_of.find(std::filesystem::path(file).filename().string());
      const std::string expected = known != hips_of.end() ? known->second : "Hips";
      REQUIRE(r.joint[kHips] >= 0);
      CHECK(clip.skeleton.joints[r.joint[kHips]].name == expected);
      ++rigs;
    }
  }
  CHECK(rigs >= 50);
}
