#pragma once
// The canonical major skeleton: at most 20 joints every take is reduced to (hips, spine, chest,
// head, and per side shoulder, elbow, wrist, hand, hip, knee, ankle, toe; "shoulder" is the
// upper arm, not the clavicle; "hips" the pelvis joint that carries the trajectory, not always
// the ROOT), and the name rules that find them in the skeleton conventions seen in practice.
#include <array>
#include <string>
#include <vector>

#include "engine/base/clip.h"

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

// How a canonical joint was found.
enum class MajorSource {
  kNone,         // not found
  kName,         // the name rules
  kStructure,    // the skeleton's structure and rest pose (rig_structure.h)
  kMappingFile,  // a mapping file's line
};
const char* major_source_name(MajorSource source);  // "name", "structure", "mapping file", "none"

// Which joint of a skeleton plays each canonical role (-1 where the skeleton has none), and how
// each was found.
struct MajorMapping {
  std::array<int, kMajorJointCount> joint;
  std::array<MajorSource, kMajorJointCount> source;
  // One sentence: how many joints each way found, what the structure found where it was read
  // (and how it told left from right), and which joints are missing.
  std::string how;
  MajorMapping() {
    joint.fill(-1);
    source.fill(MajorSource::kNone);
  }
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
// Mixamo, 3ds Max Biped, Kinect, UE, and similar); where the names leave a body part incomplete
// (the torso without hips, head, and spine or chest; a leg without hip, knee and ankle; an arm
// without shoulder, elbow and wrist), its missing joints from the skeleton's structure and rest
// pose (rig_structure.h), so parts the names read whole never change; then the overrides. The
// hips is the pelvis joint that carries the trajectory, which is not always the ROOT (failing
// names and structure, the first joint with position channels). A joint at the very same place
// as its canonical parent in the rest pose (a zero-length bone), or not below it, and a hips
// called "root" less than a quarter of the rest pose's height above its lowest joint (a root
// on the floor), are passed over for the next candidate by the name rules. Throws InputError "FILE:LINE: ..." when an override
// names a joint the skeleton does not have (listing the ones it has) or one that already plays
// another role. O(joints x spellings), and O(joints^2) where the structure is read.
MajorMapping map_major_joints(const Skeleton& skeleton, const MappingOverrides* overrides = nullptr);

// The same for a clip: where the structure is read and its rest pose does not tell which way
// the body faces, the motion tells it (the toes, the knees' bend, the root's travel), and leaf
// joints the motion never moves are end markers. O(joints^2 + frames x joints) at most.
MajorMapping map_major_joints(const Clip& clip, const MappingOverrides* overrides = nullptr);

// Whether m has every joint a blend cannot do without: the hips, both hips, knees and ankles.
bool has_needed_joints(const MajorMapping& m);

// The canonical joints two mappings share, in canonical order. Throws InputError naming the
// files and the missing joints (and which file lacks each), and how each file's joints were
// found (MajorMapping::how), when the hips, a hip, knee or ankle, or more than
// kMajorJointCount - kMinimumSharedJoints joints are missing.
constexpr int kMinimumSharedJoints = 8;
std::vector<int> shared_major_joints(const MajorMapping& a, const std::string& source_a,
                                     const MajorMapping& b, const std::string& source_b);

// Parent of each entry of `joints` (a canonical subset) within that subset: the nearest
// canonical ancestor present, -1 for the first (the hips).
std::vector<int> subset_parents(const std::vector<int>& joints);

}  // namespace mostyle
