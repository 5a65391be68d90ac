#include "engine/prepare/major_skeleton.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "engine/base/atomic_file.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "engine/io/motion_file.h"
#include "engine/kinematics/kinematics.h"
#include "tests/engine/skeleton_builder.h"
#include "tests/test_data.h"

using namespace mostyle;

namespace {

// The file's joint name of each canonical joint, "-" where the skeleton has none.
std::vector<std::string> mapped_names(const Skeleton& skeleton, const MajorMapping& mapping) {
  std::vector<std::string> out;
  for (int i = 0; i < kMajorJointCount; ++i)
    out.push_back(mapping.has(i) ? skeleton.joints[mapping.joint[i]].name : "-");
  return out;
}

std::vector<std::string> mapped_names(const Skeleton& skeleton, const MappingOverrides* o = nullptr) {
  return mapped_names(skeleton, map_major_joints(skeleton, o));
}

// Canonical order: hips spine chest head, left arm (shoulder elbow wrist hand), right arm,
// left leg (hip knee ankle toe), right leg.
const std::vector<std::string> kCmuRetargeted = {
    "Hips",       "Spine",          "Spine1",      "Head",
    "LeftArm",    "LeftForeArm",    "LeftHand",    "LeftHandIndex1",
    "RightArm",   "RightForeArm",   "RightHand",   "RightHandIndex1",
    "LeftUpLeg",  "LeftLeg",        "LeftFoot",    "LeftToeBase",
    "RightUpLeg", "RightLeg",       "RightFoot",   "RightToeBase"};
const std::vector<std::string> kBandai = {
    "Hips",       "Spine",      "Chest",   "Head",
    "UpperArm_L", "LowerArm_L", "Hand_L",  "-",
    "UpperArm_R", "LowerArm_R", "Hand_R",  "-",
    "UpperLeg_L", "LowerLeg_L", "Foot_L",  "Toes_L",
    "UpperLeg_R", "LowerLeg_R", "Foot_R",  "Toes_R"};

std::string mapping_file(const std::string& name) {
  return mostyle::test::asset("mappings/" + name);
}

MappingOverrides load_mapping(const std::string& name) {
  const std::string path = mapping_file(name);
  return parse_mapping_overrides(read_file(path), path);
}

}  // namespace

TEST_CASE("canonical joint names, parents and lookups", "[major_skeleton]") {
  CHECK(std::string(major_joint_name(0)) == "hips");
  CHECK(std::string(major_joint_name(static_cast<int>(MajorJoint::kLeftHand))) == "left_hand");
  CHECK(std::string(major_joint_name(static_cast<int>(MajorJoint::kRightToe))) == "right_toe");
  CHECK(std::string(major_joint_name(-1)) == "?");
  CHECK(std::string(major_joint_name(kMajorJointCount)) == "?");
  for (int i = 0; i < kMajorJointCount; ++i) {
    CHECK(major_joint_from_name(major_joint_name(i)) == i);
    CHECK(major_joint_parent(i) < i);  // parents before children
  }
  CHECK(major_joint_parent(0) == -1);
  CHECK(major_joint_parent(static_cast<int>(MajorJoint::kLeftShoulder)) == static_cast<int>(MajorJoint::kChest));
  CHECK(major_joint_parent(static_cast<int>(MajorJoint::kRightHip)) == static_cast<int>(MajorJoint::kHips));
  CHECK(major_joint_from_name("Hips") == -1);  // canonical names are lower case
  CHECK(major_joint_from_name("left_arm") == -1);
}

TEST_CASE("name rules: retargeted CMU skips its zero-length joints", "[major_skeleton]") {
  // LHipJoint, LowerBack, LeftShoulder, LeftFingerBase sit on their parent: never picked.
  CHECK(mapped_names(test::cmu_retargeted_skeleton()) == kCmuRetargeted);
}

TEST_CASE("name rules: Bandai's hips is Hips, not the dummy ROOT joint_Root", "[major_skeleton]") {
  const Skeleton s = test::bandai_skeleton();
  const MajorMapping m = map_major_joints(s);
  CHECK(s.joints[m.joint[0]].name == "Hips");
  CHECK(mapped_names(s, m) == kBandai);  // no hand tip; UpperArm, not the clavicle Shoulder_L
}

TEST_CASE("name rules: Mixamo", "[major_skeleton]") {
  const std::vector<std::string> expected = {
      "mixamorig:Hips",       "mixamorig:Spine",        "mixamorig:Spine2",    "mixamorig:Head",
      "mixamorig:LeftArm",    "mixamorig:LeftForeArm",  "mixamorig:LeftHand",  "mixamorig:LeftHandMiddle1",
      "mixamorig:RightArm",   "mixamorig:RightForeArm", "mixamorig:RightHand", "mixamorig:RightHandMiddle1",
      "mixamorig:LeftUpLeg",  "mixamorig:LeftLeg",      "mixamorig:LeftFoot",  "mixamorig:LeftToeBase",
      "mixamorig:RightUpLeg", "mixamorig:RightLeg",     "mixamorig:RightFoot", "mixamorig:RightToeBase"};
  CHECK(mapped_names(test::mixamo_skeleton()) == expected);
}

TEST_CASE("name rules: 3ds Max Biped", "[major_skeleton]") {
  const std::vector<std::string> expected = {
      "Bip01 Pelvis",   "Bip01 Spine",     "Bip01 Spine1",  "Bip01 Head",
      "Bip01 L UpperArm", "Bip01 L Forearm", "Bip01 L Hand", "Bip01 L Finger1",
      "Bip01 R UpperArm", "Bip01 R Forearm", "Bip01 R Hand", "Bip01 R Finger1",
      "Bip01 L Thigh",  "Bip01 L Calf",    "Bip01 L Foot",  "Bip01 L Toe0",
      "Bip01 R Thigh",  "Bip01 R Calf",    "Bip01 R Foot",  "Bip01 R Toe0"};
  CHECK(mapped_names(test::biped_skeleton()) == expected);
}

// Unreal's mannequin (UE4) as FBX and glTF exports name it; `prefix` makes Mixamo-like and
// Biped-like variants of the same tree. Twist and IK bones beside the chain must not be taken.
Skeleton unreal_skeleton() {
  test::SkeletonBuilder b;
  b.joint("root", "", 0, 0, 0)
      .joint("pelvis", "root", 0, 95, 0)
      .joint("spine_01", "pelvis", 0, 10, 0)
      .joint("spine_02", "spine_01", 0, 10, 0)
      .joint("spine_03", "spine_02", 0, 10, 0)
      .joint("neck_01", "spine_03", 0, 15, 0)
      .joint("head", "neck_01", 0, 10, 0)
      .joint("ik_foot_root", "root", 0, 0, 0)
      .joint("ik_foot_l", "ik_foot_root", 9, 8, 0);
  for (const char* side : {"l", "r"}) {
    const std::string s = side;
    const double sign = s == "l" ? 1 : -1;
    b.joint("clavicle_" + s, "spine_03", sign * 3, 12, 0)
        .joint("upperarm_" + s, "clavicle_" + s, sign * 15, 0, 0)
        .joint("upperarm_twist_01_" + s, "upperarm_" + s, sign * 5, 0, 0)
        .joint("lowerarm_" + s, "upperarm_" + s, sign * 28, 0, 0)
        .joint("hand_" + s, "lowerarm_" + s, sign * 25, 0, 0)
        .joint("middle_01_" + s, "hand_" + s, sign * 9, 0, 0)
        .joint("thigh_" + s, "pelvis", sign * 9, -3, 0)
        .joint("calf_" + s, "thigh_" + s, 0, -42, 0)
        .joint("calf_twist_01_" + s, "calf_" + s, 0, -10, 0)
        .joint("foot_" + s, "calf_" + s, 0, -42, 0)
        .joint("ball_" + s, "foot_" + s, 0, -6, 13);
  }
  return b.skeleton();
}

TEST_CASE("name rules: Unreal's mannequin (pelvis, spine_01, thigh_l, calf_l, ball_l)", "[major_skeleton]") {
  const std::vector<std::string> expected = {
      "pelvis",     "spine_01",   "spine_03", "head",
      "upperarm_l", "lowerarm_l", "hand_l",   "middle_01_l",
      "upperarm_r", "lowerarm_r", "hand_r",   "middle_01_r",
      "thigh_l",    "calf_l",     "foot_l",   "ball_l",
      "thigh_r",    "calf_r",     "foot_r",   "ball_r"};
  CHECK(mapped_names(unreal_skeleton()) == expected);
}

TEST_CASE("name rules: rig prefixes (mixamorigHips, mixamorig1:, Bip001, Blender's DEF-)", "[major_skeleton]") {
  // Mixamo without the colon (three.js and some glTF exporters drop it): "mixamorigHips".
  Skeleton mixamo = test::mixamo_skeleton();
  for (Joint& j : mixamo.joints) {
    const size_t colon = j.name.find(':');
    if (colon != std::string::npos) j.name.erase(colon, 1);
  }
  const std::vector<std::string> names = mapped_names(mixamo);
  CHECK(names[0] == "mixamorigHips");
  CHECK(names[7] == "mixamorigLeftHandMiddle1");
  CHECK(names[19] == "mixamorigRightToeBase");
  for (const char* prefix : {"mixamorig1:", "Bip001 ", "DEF-"}) {
    Skeleton s = unreal_skeleton();
    for (Joint& j : s.joints)
      if (!j.end_site) j.name = prefix + j.name;
    const std::vector<std::string> names = mapped_names(s);
    INFO(prefix);
    CHECK(names[0] == prefix + std::string("pelvis"));
    CHECK(names[13] == prefix + std::string("calf_l"));
    CHECK(names[19] == prefix + std::string("ball_r"));
  }
  // Biped's own root "Bip001" names no part.
  test::SkeletonBuilder b;
  b.joint("Bip001", "", 0, 0, 0).joint("Bip001 Pelvis", "Bip001", 0, 95, 0);
  CHECK(mapped_names(b.skeleton())[0] == "Bip001 Pelvis");
}

TEST_CASE("name rules: CMU in 3ds Max/Poser naming (no toes, no fingers)", "[major_skeleton]") {
  const std::vector<std::string> expected = {
      "hip",    "abdomen",  "chest", "head",
      "lShldr", "lForeArm", "lHand", "-",
      "rShldr", "rForeArm", "rHand", "-",
      "lThigh", "lShin",    "lFoot", "-",  // lThigh, not the pelvis-side lButtock
      "rThigh", "rShin",    "rFoot", "-"};
  CHECK(mapped_names(test::cmu_poser_skeleton()) == expected);
}

TEST_CASE("name rules: Kinect v1 (wrist before hand, ankle before foot)", "[major_skeleton]") {
  const std::vector<std::string> expected = {
      "HipCenter",    "Spine",      "ShoulderCenter", "Head",
      "ShoulderLeft", "ElbowLeft",  "WristLeft",      "HandLeft",
      "ShoulderRight", "ElbowRight", "WristRight",    "HandRight",
      "HipLeft",      "KneeLeft",   "AnkleLeft",      "FootLeft",
      "HipRight",     "KneeRight",  "AnkleRight",     "FootRight"};
  CHECK(mapped_names(test::kinect_skeleton()) == expected);
}

TEST_CASE("name rules: a skeleton without toes or hand tips", "[major_skeleton]") {
  const Skeleton s = test::no_toes_no_hands_skeleton();
  const std::vector<std::string> expected = {
      "Hips",      "Spine",        "Chest",     "Head",
      "LeftArm",   "LeftForeArm",  "LeftHand",  "-",  // the End Site below LeftHand is no joint
      "RightArm",  "RightForeArm", "RightHand", "-",
      "LeftUpLeg", "LeftLeg",      "LeftFoot",  "-",
      "RightUpLeg", "RightLeg",    "RightFoot", "-"};
  CHECK(mapped_names(s) == expected);
  // Paired with a full skeleton, the blend uses the 16 joints both have.
  const MajorMapping a = map_major_joints(test::cmu_retargeted_skeleton());
  const MajorMapping b = map_major_joints(s);
  const std::vector<int> shared = shared_major_joints(a, "a.bvh", b, "b.bvh");
  CHECK(shared.size() == 16);
  for (int major : shared) {
    CHECK(major != static_cast<int>(MajorJoint::kLeftHand));
    CHECK(major != static_cast<int>(MajorJoint::kRightToe));
  }
}

TEST_CASE("name rules: a skeleton without pelvis names takes the joint with position channels",
          "[major_skeleton]") {
  test::SkeletonBuilder b;
  b.joint("Body", "", 0, 95, 0)
      .joint("LeftUpLeg", "Body", 9, -5, 0)
      .joint("LeftLeg", "LeftUpLeg", 0, -42, 0)
      .joint("LeftFoot", "LeftLeg", 0, -42, 0);
  const MajorMapping m = map_major_joints(b.skeleton());
  CHECK(m.joint[0] == 0);
  CHECK(m.joint[static_cast<int>(MajorJoint::kLeftKnee)] == 2);
}

TEST_CASE("name rules on the bundled CMU takes and the shared CMU and Bandai takes", "[major_skeleton]") {
  for (const std::string& path : test::asset_motions()) {
    INFO(path);
    const Clip clip = read_bvh_file(path);
    CHECK(mapped_names(clip.skeleton) == kCmuRetargeted);
  }
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  int bandai = 0, cmu = 0;
  for (const std::string& path : test::shared_motions()) {
    INFO(path);
    const Clip clip = read_bvh_file(path);
    const bool is_bandai = path.find("bandai_") != std::string::npos;
    CHECK(mapped_names(clip.skeleton) == (is_bandai ? kBandai : kCmuRetargeted));
    (is_bandai ? bandai : cmu) += 1;
  }
  CHECK(bandai == 7);
  CHECK(cmu == 4);
}

TEST_CASE("shared joints across conventions: CMU and Bandai share 18", "[major_skeleton]") {
  const MajorMapping cmu = map_major_joints(test::cmu_retargeted_skeleton());
  const MajorMapping bandai = map_major_joints(test::bandai_skeleton());
  const std::vector<int> shared = shared_major_joints(cmu, "cmu.bvh", bandai, "bandai.bvh");
  std::vector<int> expected;
  for (int i = 0; i < kMajorJointCount; ++i)
    if (i != static_cast<int>(MajorJoint::kLeftHand) && i != static_cast<int>(MajorJoint::kRightHand))
      expected.push_back(i);
  CHECK(shared == expected);
}

TEST_CASE("missing joints: the error lists each one and which take lacks it", "[major_skeleton]") {
  const MajorMapping full = map_major_joints(test::cmu_retargeted_skeleton());
  SECTION("a leg joint missing in B") {
    MajorMapping b = full;
    b.joint[static_cast<int>(MajorJoint::kLeftKnee)] = -1;
    b.joint[static_cast<int>(MajorJoint::kRightHand)] = -1;
    try {
      shared_major_joints(full, "walk_a.bvh", b, "walk_b.bvh");
      FAIL("expected an InputError");
    } catch (const InputError& e) {
      const std::string m = e.what();
      INFO(m);
      CHECK(m.rfind("walk_a.bvh and walk_b.bvh: too few major joints to blend", 0) == 0);
      CHECK(m.find("missing: left_knee (walk_b.bvh)") != std::string::npos);
      CHECK(m.find("also missing: right_hand (walk_b.bvh)") != std::string::npos);
      CHECK(m.find("the hips, both hips, knees and ankles") != std::string::npos);
      CHECK(m.find("mapping file") != std::string::npos);
      CHECK(m.find("--mapping-a") != std::string::npos);
    }
  }
  SECTION("too few joints in all, missing in both") {
    test::SkeletonBuilder legs;
    legs.joint("Hips", "", 0, 95, 0);
    for (const char* side : {"Left", "Right"}) {
      const std::string s = side;
      legs.joint(s + "UpLeg", "Hips", s == "Left" ? 9 : -9, -5, 0)
          .joint(s + "Leg", s + "UpLeg", 0, -42, 0)
          .joint(s + "Foot", s + "Leg", 0, -42, 0);
    }
    const MajorMapping m = map_major_joints(legs.skeleton());
    try {
      shared_major_joints(m, "legs.bvh", m, "legs2.bvh");
      FAIL("expected an InputError");
    } catch (const InputError& e) {
      const std::string text = e.what();
      INFO(text);
      CHECK(text.find("found 7") != std::string::npos);
      CHECK(text.find("spine (both)") != std::string::npos);
      CHECK(text.find("right_toe (both)") != std::string::npos);
    }
  }
  SECTION("one take with itself names it once") {
    MajorMapping a = full;
    a.joint[0] = -1;
    try {
      shared_major_joints(a, "walk.bvh", a, "walk.bvh");
      FAIL("expected an InputError");
    } catch (const InputError& e) {
      const std::string text = e.what();
      INFO(text);
      CHECK(text.rfind("walk.bvh: too few major joints", 0) == 0);
      CHECK(text.find("hips (walk.bvh)") != std::string::npos);
    }
  }
  // Exactly the required 7 plus one more is enough.
  MajorMapping eight;
  for (int i : {0, 1, 12, 13, 14, 16, 17, 18}) eight.joint[i] = full.joint[i];
  CHECK(shared_major_joints(eight, "a", eight, "b").size() == 8);
}

TEST_CASE("subset parents skip the canonical joints a take lacks", "[major_skeleton]") {
  // hips, chest (no spine), head, left shoulder, left wrist (no elbow), left hip.
  const std::vector<int> joints = {0, 2, 3, 4, 6, 12};
  CHECK(subset_parents(joints) == std::vector<int>{-1, 0, 1, 1, 3, 0});
  std::vector<int> all(kMajorJointCount);
  for (int i = 0; i < kMajorJointCount; ++i) all[i] = i;
  const std::vector<int> parents = subset_parents(all);
  for (int i = 0; i < kMajorJointCount; ++i) CHECK(parents[i] == major_joint_parent(i));
}

TEST_CASE("mapping files: parsing", "[major_skeleton]") {
  const MappingOverrides o = parse_mapping_overrides(
      "# my rig\r\n\r\nhips = Pelvis   # the pelvis\r\n  left_elbow=Bip01 L Forearm\r\nleft_hand = -\r\n",
      "rig.txt");
  CHECK(o.source == "rig.txt");
  REQUIRE(o.entries.size() == 3);
  CHECK(o.entries[0] == std::make_pair(0, std::string("Pelvis")));
  CHECK(o.entries[1] == std::make_pair(static_cast<int>(MajorJoint::kLeftElbow), std::string("Bip01 L Forearm")));
  CHECK(o.entries[2] == std::make_pair(static_cast<int>(MajorJoint::kLeftHand), std::string("-")));
  CHECK(o.lines == std::vector<int>{3, 4, 5});
  CHECK(parse_mapping_overrides("", "empty.txt").entries.empty());
  CHECK(parse_mapping_overrides("# only a comment", "c.txt").entries.empty());
}

TEST_CASE("mapping files: every malformed line is an error with file and line", "[major_skeleton]") {
  auto error_of = [](const std::string& text) {
    try {
      parse_mapping_overrides(text, "rig.txt");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error_of("hips = Hips\nLeftArm\n") ==
        "rig.txt:2: expected 'canonical_joint = FileJoint', found 'LeftArm'");
  CHECK(error_of("\n\nleft_arm = LeftArm") ==
        "rig.txt:3: expected a canonical joint name (hips, spine, chest, head, left_shoulder .. "
        "right_toe), found 'left_arm'");
  CHECK(error_of("Hips = Hips") ==
        "rig.txt:1: expected a canonical joint name (hips, spine, chest, head, left_shoulder .. "
        "right_toe), found 'Hips'");
  CHECK(error_of("hips =   # nothing") == "rig.txt:1: expected a joint name after '=', found nothing");
  CHECK(error_of("left_knee = LeftLeg\r\nhips = Hips\r\nleft_knee = RightLeg\r\n") ==
        "rig.txt:3: left_knee is mapped a second time (first on line 1)");
}

TEST_CASE("mapping files: overrides replace, remove and swap what the name rules found",
          "[major_skeleton]") {
  const Skeleton s = test::cmu_retargeted_skeleton();
  SECTION("replace and remove") {
    const MappingOverrides o = parse_mapping_overrides(
        "left_hand = -\nchest = Neck1\nleft_wrist = LeftHandIndex1\n", "o.txt");
    std::vector<std::string> expected = kCmuRetargeted;
    expected[static_cast<int>(MajorJoint::kLeftHand)] = "-";
    expected[static_cast<int>(MajorJoint::kChest)] = "Neck1";
    expected[static_cast<int>(MajorJoint::kLeftWrist)] = "LeftHandIndex1";
    CHECK(mapped_names(s, &o) == expected);
  }
  SECTION("swap two joints") {
    const MappingOverrides o = parse_mapping_overrides(
        "left_knee = RightLeg\nright_knee = LeftLeg\n", "swap.txt");
    std::vector<std::string> expected = kCmuRetargeted;
    std::swap(expected[static_cast<int>(MajorJoint::kLeftKnee)], expected[static_cast<int>(MajorJoint::kRightKnee)]);
    CHECK(mapped_names(s, &o) == expected);
  }
  SECTION("a joint the skeleton does not have") {
    const MappingOverrides o = parse_mapping_overrides("hips = Hips\n\nleft_elbow = LeftForearm\n", "o.txt");
    try {
      map_major_joints(s, &o);
      FAIL("expected an InputError");
    } catch (const InputError& e) {
      const std::string m = e.what();
      INFO(m);
      CHECK(m.rfind("o.txt:3: expected a joint of the skeleton for left_elbow, found 'LeftForearm' "
                    "(the skeleton has Hips, LHipJoint, LeftUpLeg,", 0) == 0);
      CHECK(m.find("End Site") == std::string::npos);
    }
  }
  SECTION("a joint that already plays another role") {
    const MappingOverrides o = parse_mapping_overrides("# hand\nleft_hand = LeftHand\n", "o.txt");
    CHECK_THROWS_WITH(map_major_joints(s, &o),
                      Catch::StartsWith("o.txt:2: joint 'LeftHand' is already left_wrist; a joint plays one role"));
  }
  SECTION("an End Site is not a joint") {
    const MappingOverrides o = parse_mapping_overrides("head = Head End Site\n", "o.txt");
    CHECK_THROWS_WITH(map_major_joints(s, &o), Catch::StartsWith("o.txt:1: expected a joint of the skeleton"));
  }
}

TEST_CASE("mapping files in assets/mappings work on their conventions", "[major_skeleton]") {
  SECTION("cmu.txt on the bundled takes") {
    const MappingOverrides o = load_mapping("cmu.txt");
    CHECK(o.entries.size() == kMajorJointCount);
    for (const std::string& path : test::asset_motions()) {
      INFO(path);
      CHECK(mapped_names(read_bvh_file(path).skeleton, &o) == kCmuRetargeted);
    }
  }
  SECTION("the synthetic conventions: the file agrees with the name rules") {
    const std::pair<const char*, Skeleton> cases[] = {
        {"cmu.txt", test::cmu_retargeted_skeleton()},
        {"bandai.txt", test::bandai_skeleton()},
        {"mixamo.txt", test::mixamo_skeleton()},
        {"biped.txt", test::biped_skeleton()},
        {"cmu_poser.txt", test::cmu_poser_skeleton()},
    };
    for (const auto& [file, skeleton] : cases) {
      INFO(file);
      const MappingOverrides o = load_mapping(file);
      CHECK(o.entries.size() == kMajorJointCount);
      CHECK(mapped_names(skeleton, &o) == mapped_names(skeleton));
    }
  }
  SECTION("a file for another convention fails with file and line") {
    const MappingOverrides o = load_mapping("bandai.txt");
    CHECK_THROWS_WITH(map_major_joints(test::cmu_retargeted_skeleton(), &o),
                      Catch::StartsWith(mapping_file("bandai.txt") + ":5: expected a joint of the skeleton for chest, found 'Chest'"));
  }
  SECTION("bandai.txt on the shared Bandai takes") {
    MOSTYLE_REQUIRE_SHARED_MOTIONS();
    const MappingOverrides o = load_mapping("bandai.txt");
    for (const std::string& path : test::shared_motions()) {
      if (path.find("bandai_") == std::string::npos) continue;
      INFO(path);
      CHECK(mapped_names(read_bvh_file(path).skeleton, &o) == kBandai);
    }
  }
}

TEST_CASE("names and structure: names keep a body part they read whole, the structure fills the rest",
          "[major_skeleton]") {
  SECTION("Aalto's torso: hips, chest and head by name, its spine 'Ab' left out as before") {
    test::SkeletonBuilder b;
    b.joint("Hips", "", 0, 95, 0)
        .joint("Ab", "Hips", 0, 8, 0)
        .joint("Chest", "Ab", 0, 25, 0)
        .joint("Neck", "Chest", 0, 25, 0)
        .joint("Head", "Neck", 0, 11, 0)
        .end("Head", 0, 17, 0);
    for (const char* side : {"Left", "Right"}) {
      const std::string s = side;
      const double sign = s == "Left" ? 1 : -1;
      b.joint(s + "Collar", "Chest", 0, 25, 0)
          .joint(s + "Shoulder", s + "Collar", sign * 20, 0, 0)
          .joint(s + "Elbow", s + "Shoulder", sign * 27, 0, 0)
          .joint(s + "Wrist", s + "Elbow", sign * 23, 0, 0)
          .end(s + "Wrist", 0, -15, 0);
      b.joint(s + "Hip", "Hips", sign * 12, 0, 0)
          .joint(s + "Knee", s + "Hip", 0, -41, 0)
          .joint(s + "Ankle", s + "Knee", 0, -44, 0)
          .end(s + "Ankle", 0, -5, 17);
    }
    const MajorMapping m = map_major_joints(b.skeleton());
    const std::vector<std::string> names = mapped_names(b.skeleton(), m);
    CHECK(names == std::vector<std::string>{"Hips", "-", "Chest", "Head", "LeftShoulder", "LeftElbow", "LeftWrist", "-",
                                            "RightShoulder", "RightElbow", "RightWrist", "-", "LeftHip", "LeftKnee",
                                            "LeftAnkle", "-", "RightHip", "RightKnee", "RightAnkle", "-"});
    for (int i = 0; i < kMajorJointCount; ++i)
      CHECK(m.source[i] == (m.has(i) ? MajorSource::kName : MajorSource::kNone));
    CHECK(m.how == "15 by name; missing: spine, left_hand, right_hand, left_toe, right_toe");
  }
  SECTION("a leg the names do not read: from the structure, the rest by name") {
    Skeleton s = test::cmu_retargeted_skeleton();
    for (const char* name : {"RHipJoint", "RightUpLeg", "RightLeg", "RightFoot", "RightToeBase"})
      s.joints[s.find(name)].name = std::string("x_") + std::to_string(s.find(name));
    const MajorMapping m = map_major_joints(s);
    const MajorMapping named = map_major_joints(test::cmu_retargeted_skeleton());
    for (int i = 0; i < kMajorJointCount; ++i) {
      INFO(major_joint_name(i));
      CHECK(m.joint[i] == named.joint[i]);
      CHECK(m.source[i] == (i >= static_cast<int>(MajorJoint::kRightHip) ? MajorSource::kStructure : MajorSource::kName));
    }
    CHECK(m.how.rfind("16 by name, 4 by structure (structure: hips 'Hips' with two legs", 0) == 0);
  }
  SECTION("a mapping file's lines are told as such") {
    const MappingOverrides o = parse_mapping_overrides("chest = Neck1\nleft_hand = -\n", "o.txt");
    const MajorMapping m = map_major_joints(test::cmu_retargeted_skeleton(), &o);
    CHECK(m.source[static_cast<int>(MajorJoint::kChest)] == MajorSource::kMappingFile);
    CHECK(m.source[static_cast<int>(MajorJoint::kLeftHand)] == MajorSource::kMappingFile);
    CHECK_FALSE(m.has(static_cast<int>(MajorJoint::kLeftHand)));
    CHECK(m.how == "18 by name, 1 from the mapping file; missing: left_hand");
    CHECK(std::string(major_source_name(MajorSource::kMappingFile)) == "mapping file");
  }
  SECTION("a rig that cannot be read says what was found and what is missing") {
    test::SkeletonBuilder b;
    b.joint("a", "", 0, 100, 0).joint("b", "a", 0, -30, 0).joint("c", "b", 0, -30, 0);
    const MajorMapping m = map_major_joints(b.skeleton());
    try {
      shared_major_joints(m, "snake.glb", map_major_joints(test::cmu_retargeted_skeleton()), "walk.bvh");
      FAIL("expected an InputError");
    } catch (const InputError& e) {
      const std::string text = e.what();
      INFO(text);
      CHECK(text.find("snake.glb: 1 by structure (structure: no legs: no joint has two chains") != std::string::npos);
      CHECK(text.find("walk.bvh: 20 by name") == std::string::npos);  // nothing needed missing there
    }
  }
}

TEST_CASE("the wild files: one skeleton per file, the major joints found, left on the body's left",
          "[major_skeleton][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  struct Wild {
    const char* file;
    std::vector<std::string> gaits;  // the walk and run takes ("" for the file's only one)
    MajorSource source;              // how its legs are found
  };
  const std::vector<Wild> wild = {
      {"gltf_cesiumman_walk.glb", {""}, MajorSource::kStructure},
      {"gltf_godot_robot_walk_run.glb", {"walk", "run"}, MajorSource::kName},
      {"gltf_mannequiny_run.glb", {"run_root.001"}, MajorSource::kName},
      {"gltf_godot_mixamo_walk_run.glb", {"walking", "running"}, MajorSource::kName},
      {"fbx_mixamo_walking.fbx", {""}, MajorSource::kName},
      {"xia_sexy_01.bvh", {""}, MajorSource::kName},
      {"xia_angry_13.bvh", {""}, MajorSource::kName},
      {"xia_old_13.bvh", {""}, MajorSource::kName},
      {"xia_depressed_13.bvh", {""}, MajorSource::kName},
      {"xia_neutral_16.bvh", {""}, MajorSource::kName},  // a jump: the knees bend forward too
      {"aalto_t_walk_regular.bvh", {""}, MajorSource::kName},
      {"aalto_k_walk_fast.bvh", {""}, MajorSource::kName},
      {"aalto_k_walk_slow.bvh", {""}, MajorSource::kName},
  };
  for (const Wild& w : wild) {
    const std::string path = test::shared_motion("wild/" + std::string(w.file));
    INFO(path);
    // Every take on one skeleton.
    std::vector<std::string> joints;
    for (const TakeInfo& take : read_motion_takes(path)) {
      const Clip clip = read_motion_file(path, nullptr, [&] {
        MotionReadOptions o;
        o.take = motion_format(path) == MotionFormat::kBvh ? "" : take.name;
        return o;
      }());
      std::vector<std::string> names;
      for (const Joint& j : clip.skeleton.joints) names.push_back(j.name);
      if (joints.empty()) joints = names;
      CHECK(names == joints);
    }
    for (const std::string& gait : w.gaits) {
      INFO(gait);
      const Clip clip = read_motion_file(gait.empty() ? path : path + "#" + gait);
      const MajorMapping m = map_major_joints(clip);
      INFO(m.how);
      for (int major : {0, 12, 13, 14, 16, 17, 18}) CHECK(m.has(major));
      CHECK(m.source[static_cast<int>(MajorJoint::kLeftKnee)] == w.source);
      // Left is left: over the take, the knees bend forward of the line from hip to ankle, where
      // forward is the way the body faces if the left hip is on its left (left = up x forward).
      const Eigen::MatrixXd p = joint_positions(clip);
      const auto at = [&](Eigen::Index f, int major) {
        return Eigen::Vector3d(p.block<1, 3>(f, 3 * m.joint[major]).transpose());
      };
      double bend = 0.0;
      for (Eigen::Index f = 0; f < p.rows(); ++f) {
        Eigen::Vector3d lateral = at(f, 12) - at(f, 16);
        lateral.y() = 0;
        const Eigen::Vector3d forward = lateral.normalized().cross(Eigen::Vector3d::UnitY());
        for (int hip : {12, 16}) {
          const Eigen::Vector3d h = at(f, hip), k = at(f, hip + 1), a = at(f, hip + 2);
          const double s = (k - h).dot(a - h) / (a - h).squaredNorm();
          bend += (k - (h + s * (a - h))).dot(forward);
        }
      }
      CHECK(bend > 0);
    }
  }
  // The same Cesium Man without its rest rotations (a BVH written from it: every rotation zero
  // is no standing body there, its bones run along their own axes): read in its first frame.
  Clip cesium = read_motion_file(test::shared_motion("wild/gltf_cesiumman_walk.glb"));
  const MajorMapping from_rest = map_major_joints(cesium);
  for (Joint& j : cesium.skeleton.joints) j.rest_rotation.setIdentity();
  const MajorMapping from_first_frame = map_major_joints(cesium);
  CHECK(from_first_frame.joint == from_rest.joint);
  CHECK_THAT(from_first_frame.how, Catch::Contains("read in the first frame's pose") &&
                                       Catch::Contains("left told by the knees' bend over the motion"));
  // And begun at any frame of its loop, a foot in the air on the first (a walk cut mid-stride):
  // read in a pose of the motion that stands on both legs.
  int from_later = 0;
  for (Eigen::Index start = 0; start < cesium.motion.rows(); ++start) {
    INFO("begun at frame " << start);
    Clip cut = cesium;
    const Eigen::Index n = cesium.motion.rows();
    cut.motion.topRows(n - start) = cesium.motion.bottomRows(n - start);
    cut.motion.bottomRows(start) = cesium.motion.topRows(start);
    const MajorMapping m = map_major_joints(cut);
    CHECK(m.joint == from_rest.joint);
    from_later += m.how.find("a pose of the motion that stands on both legs") != std::string::npos;
  }
  CHECK(from_later > 0);  // some frames have a foot in the air
}
