#pragma once
// The canonical major skeleton (DESIGN.md 2): at most 20 joints every take is reduced to, and
// the name rules that find them in the skeleton conventions seen in practice.
#include <array>
#include <string>
#include <vector>

#include "engine/io/clip.h"

namespace mostyle {

constexpr int kMajorJointCount = 20;

// Index order of the canonical joints; parents come before children.
enum class MajorJoint {
  kHips, kSpine, kChest, kHead,
  kLeftShoulder, kLeftElbow, kLeftWrist, kLeftHand,
  kRightShoulder, kRightElbow, kRightWrist, kRightHand,
  kLeftHip, kLeftKnee, kLeftAnkle, kLeftToe,
  kRightHip, kRightKnee, kRightAnkle, kRightToe,
};

const char* major_joint_name(int major);  // "hips", "left_elbow", ...
int major_joint_from_name(const std::string& name);  // -1 when not a canonical name
int major_joint_parent(int major);         // canonical parent, -1 for hips

// Which joint of a skeleton plays each canonical role (-1 where the skeleton has none).
struct MajorMapping {
  std::array<int, kMajorJointCount> joint;
  MajorMapping() { joint.fill(-1); }
  bool has(int major) const { return joint[major] >= 0; }
};

// Overrides read from a mapping file: lines "left_elbow = LeftForeArm" (canonical name, then the
// file's joint name; '#' starts a comment; "left_hand = -" says the skeleton has none).
// The format is described in assets/mappings/README.md.
struct MappingOverrides {
  std::vector<std::pair<int, std::string>> entries;  // (major, joint name or "-")
  std::vector<int> lines;                            // 1-based line of each entry in `source`
  std::string source;
};
// Throws InputError "FILE:LINE: expected ..., found ..." on a malformed line, an unknown canonical
// name, a missing joint name, or a canonical joint named twice.
MappingOverrides parse_mapping_overrides(const std::string& text, const std::string& source);

// Finds the canonical joints by name rules (retargeted CMU, CMU in 3ds Max/Poser naming, Bandai,
// Mixamo, 3ds Max Biped, Kinect, and similar), then applies the overrides. The hips is the pelvis
// joint that carries the trajectory, which is not always the ROOT. A joint at the very same place
// as its canonical parent in the rest pose (a zero-length bone), or not below it, is passed over
// for the next candidate. A leg or arm that no rule finds but whose joints are numbered along it
// ("leg_joint_L_1" .. "leg_joint_L_5") is read in its chain's order: hip, knee, ankle, toe
// (shoulder, elbow, wrist, hand). Throws InputError "FILE:LINE: ..." when an override names a joint the
// skeleton does not have (listing the ones it has) or one that already plays another role.
// O(joints x spellings).
MajorMapping map_major_joints(const Skeleton& skeleton, const MappingOverrides* overrides = nullptr);

// The canonical joints two mappings share, in canonical order. Throws InputError naming the
// files and the missing joints (and which file lacks each) when the hips, a hip, knee or ankle,
// or more than kMajorJointCount - kMinimumSharedJoints joints are missing.
constexpr int kMinimumSharedJoints = 8;
std::vector<int> shared_major_joints(const MajorMapping& a, const std::string& source_a,
                                     const MajorMapping& b, const std::string& source_b);

// Parent of each entry of `joints` (a canonical subset) within that subset: the nearest
// canonical ancestor present, -1 for the first (the hips).
std::vector<int> subset_parents(const std::vector<int>& joints);

}  // namespace mostyle
