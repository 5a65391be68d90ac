#pragma once
// What two takes are aligned on. The paper aligns on the left foot, which suits
// locomotion; for other actions (waving, raising hands) the foot carries no timing, so the
// joints that actually move are used, weighted by how much they move.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/prepare/canonical_frame.h"

namespace mostyle {

enum class AlignOn { kAuto, kLeftFoot, kFeet, kHands, kBody };
const char* align_on_name(AlignOn on);        // "auto", "left-foot", "feet", "hands", "body"
AlignOn parse_align_on(const std::string& name);  // throws InputError naming the choices

// Columns (within the major joints) the choices use; -1 where the takes have none.
struct FeatureJoints {
  int left_ankle = -1, right_ankle = -1, left_wrist = -1, right_wrist = -1;
};

struct AlignmentFeature {
  AlignOn on = AlignOn::kLeftFoot;  // what was used (never kAuto)
  bool locomotion = false;          // both takes travel (what kAuto decides on)
  std::vector<int> columns;         // joint columns used
  std::vector<double> weights;      // per column, 0..1
  Eigen::MatrixXd a, b;             // Fa x 3c, Fb x 3c: weighted canonical positions, A's units
};

// A take counts as locomotion when its hips travel at least this many leg lengths per second
// on average (a slow, old walk travels about 0.8; waving in place about 0).
constexpr double kLocomotionLegsPerSecond = 0.25;
// kBody keeps the joints whose motion (RMS deviation from their mean) is at least this
// fraction of the most moving joint's, at most kBodyMaxJoints of them.
constexpr double kBodyMinWeight = 0.4;
constexpr int kBodyMaxJoints = 6;

// a, b: the two takes in the canonical frame (B retargeted to A's bones), leg_length in A's
// units, fps their rate. kAuto picks kLeftFoot when both takes are locomotion, else kBody.
// Throws InputError when the chosen joints are missing.
AlignmentFeature alignment_feature(const CanonicalMotion& a, const CanonicalMotion& b, const FeatureJoints& joints,
                                   AlignOn on, double leg_length, double fps);

// Mean hips ground speed of a take, leg lengths per second.
double travel_speed(const CanonicalMotion& motion, double leg_length, double fps);

}  // namespace mostyle
