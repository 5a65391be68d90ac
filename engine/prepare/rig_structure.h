#pragma once
// The major joints of a rig found from its shape rather than its names: the hierarchy, the rest
// pose (Y up, as everywhere in the engine; where the rest pose shows no legs, the first frame's
// pose, or the first frame sampled over the motion that stands on both) and, where the pose
// cannot tell which way the body faces, the motion. map_major_joints (major_skeleton.h) fills
// from here what the name rules leave out.
//   legs: the two chains that go down from one joint (the hips) to the floor (the lowest joint),
//     side by side under it, whatever their share of the height (a robot's or a cartoon's legs
//     may be a fifth of it, and its arms hang lower than its hips), each cut at its two longest
//     consecutive bones (thigh and shin): hip, knee, ankle, then the toe;
//     a leg whose shin ends with no foot under it (an IK rig, whose foot joint hangs from the
//     root) takes the joint nearest the shin's end as its ankle;
//   spine: the chain that goes up from the hips to the highest joint (the head's end); the
//     arms: the two chains that leave it sideways at one joint (the chest), each cut at its two
//     longest consecutive bones (upper arm and forearm): shoulder, elbow, wrist, then the hand;
//     the spine joint a third of the way from the hips to the chest; the head the last joint
//     above the chest that is not an end marker (a leaf the motion never moves);
//   left and right: from the body's facing: the way the toes point in the rest pose, the knees'
//     bend in it, then over the motion the knees' bend (knees bend forward), the planted foot's
//     slide under the body, the root's travel and the toes; where none tells, the side the
//     names give, else +Z as the facing. Whether the names' sides agree is told apart.
#include <array>
#include <string>
#include <vector>

#include "engine/base/clip.h"
#include "engine/prepare/major_skeleton.h"

namespace mostyle {

// What told which leg is the left one.
enum class FacingCue {
  kNone,         // no legs, or nothing told: +Z is taken as the facing
  kNames,        // joints named left or right lie in the chains
  kRestToes,     // the toes point forward in the rest pose
  kRestKnees,    // the knees bend forward in the rest pose
  kMotionKnees,  // the knees bend forward over the motion
  kMotionSlide,  // the planted foot moves backward under the body over the motion
  kTravel,       // the root travels forward over the motion
  kMotionToes,   // the toes point forward over the motion
};
const char* facing_cue_name(FacingCue cue);  // "the toes in the rest pose", ...

struct RigStructure {
  std::array<int, kMajorJointCount> joint;  // the skeleton's joint for each canonical joint, -1 where not found
  FacingCue facing = FacingCue::kNone;
  // Whether the joints the names call left lie on the body's left as its facing tells: 1 they
  // do, -1 they lie on its right (names given from the viewer's side, or a mirrored rig), 0 not
  // told (no sided names in the limbs, or the body's cues disagree among themselves).
  int names_sides = 0;
  // One sentence: what was found (the hips, legs, spine, arms, head) and from what the left side
  // was told, and what could not be found and why.
  std::string summary;
  RigStructure() { joint.fill(-1); }
};

// Finds the canonical joints of `skeleton` from its structure and rest pose (rest_positions).
// motion: frames x channels of a clip on that skeleton, or null: over its frames the facing is
// read where the rest pose does not tell it, and a leaf joint whose channels never change is an
// end marker (not taken as the head or a hand). named: the name rules' mapping, or null: joints
// it names left or right tell the sides where the body does not, and are checked against the
// body's facing (RigStructure::names_sides). End Sites are never mapped, but mark where a
// chain ends. Never throws: what is not found is -1, and the summary says why.
// O(joints^2 + frames x joints) (the motion is read only when the rest pose cannot tell the facing).
RigStructure find_rig_structure(const Skeleton& skeleton, const MotionMatrix* motion = nullptr,
                                const MajorMapping* named = nullptr);

}  // namespace mostyle
