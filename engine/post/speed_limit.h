#pragma once
// A speed limit on a motion's joints (beyond the paper): no pops. A mix, above all a transfer kept
// on its content's timing, can move a joint faster than any take does (a style's slow knee lift
// laid onto a quicker walk's cycles). Where a joint's step between two frames is faster than the
// limit, the part over it is spread over the neighbouring steps, so the joint reaches the same
// place a few frames on, moving no faster than the limit; frames beyond those few are left
// exactly as they were.
#include <Eigen/Core>
#include <vector>

#include "engine/kinematics/limb_length.h"

namespace mostyle {

// A joint may move this many times the mixed takes' fastest joint (fastest_joint.h).
constexpr double kSpeedLimitOverTakes = 1.2;
// The farthest a step's excess is spread, each way, in seconds.
constexpr double kSpeedLimitSpreadSeconds = 0.15;

// Limits every joint's speed relative to the root (column 0, whose own path is kept) in world
// (F x 3M, at fps) to `limit` file units per second less the root's own speed on that step: a
// step over it keeps `limit`'s worth along its direction and gives the rest to the steps around
// it (as many as needed, up to kSpeedLimitSpreadSeconds each way, in equal shares), so positions
// outside that window do not change. Bone lengths drift by a little where it acts: apply the
// limb-length constraint after. limit <= 0 or fewer than 3 frames: nothing. Returns the steps
// changed. O(F x M x w); no allocation once the scratch has F rows.
struct SpeedLimitScratch {
  std::vector<double> allowed;  // F - 1: what each step may move relative to the root
  Eigen::MatrixXd steps;        // F - 1 x 3: one joint's steps relative to the root
};
int limit_joint_speed(Eigen::MatrixXd& world, double fps, double limit, SpeedLimitScratch& scratch);

// Passes of limit_speed_keeping_bones.
constexpr int kSpeedLimitPasses = 8;

// limit_joint_speed with the bones' lengths held (apply_limb_lengths) after each pass, up to
// kSpeedLimitPasses passes, stopping at the first that changes nothing. Holding a bone's length
// moves its child back along the bone, and so gives back part of what the limit took from a joint
// that a fast turn of its parent's bone carries (a toe swung round its ankle); the next pass takes
// it again. Returns the passes that changed something.
// Test: "speed limit with bones kept: a child swung round its parent ends nearer the limit than one pass" (speed_limit_test.cpp).
int limit_joint_speed_keeping_bones(Eigen::MatrixXd& world, double fps, double limit, const std::vector<int>& parents,
                                    const std::vector<double>& lengths, const LimbLengthOptions& limbs,
                                    SpeedLimitScratch& scratch);

}  // namespace mostyle
