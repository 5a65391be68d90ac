#pragma once
// A take's root path as steps in its own body frame and back: what lets root paths be warped,
// matched and blended whatever direction each take walks in (the canonical frame keeps the path
// apart from the poses, canonical_frame.h).
#include <Eigen/Core>

#include "engine/prepare/canonical_frame.h"

namespace mostyle {

// Root steps, the per-frame root motion in the body frame: row t = (vx, vz, turn) takes frame t
// to t + 1 (ground step rotated into frame t's heading, heading change); the last row is zero.
// F x 3, file units and radians per frame. Blending steps blends speed and turning, whatever
// direction each take walks in.
Eigen::MatrixXd root_steps(const CanonicalMotion& motion);
Eigen::MatrixXd root_steps(const Eigen::MatrixXd& ground, const Eigen::VectorXd& heading);

// Integrates steps (F x 3) from a start position (x, z) and heading into ground (F x 2) and
// heading (F). The inverse of root_steps: integrating a take's own steps from its first frame
// gives its ground and heading back (up to rounding).
void integrate_root(const Eigen::MatrixXd& steps, const Eigen::Vector2d& start_ground,
                    double start_heading, Eigen::MatrixXd* ground, Eigen::VectorXd* heading);

// B's root steps on A's timeline (F x 3: root_steps of B's ground and heading warped onto A's F
// frames) with the ground part of each step limited to what max_speedup of B's own frames cover.
// warp: F values, B's (fractional) frame shown at each A frame (dtw.h warp_map). Where the warp
// runs over more than max_speedup B frames in one A frame, B's pose jumps over the frames in
// between, and its root should not walk them in that one frame: where a long B is squeezed onto a
// short A, the DTW skips up to a hundred frames at once and the root would teleport by metres.
// Such a step keeps its direction and is scaled by max_speedup / (B frames skipped); the turn is
// kept whole, so B faces the way its pose does. Throws InputError when the shapes differ. O(F).
constexpr double kMaxWarpSpeedup = 4.0;
Eigen::MatrixXd limit_warped_steps(const Eigen::MatrixXd& steps, const Eigen::VectorXd& warp,
                                   double max_speedup);

// B's root steps (F x 3, on A's timeline, from root_steps) with turns changed by whole turns
// (multiples of 2 pi) so that the heading they integrate to stays within about pi of the heading
// A's steps (F x 3) integrate to, from the same start: B's path and facing are unchanged (whole
// turns are invisible), but blending the turn channel then blends the two facings along the
// shorter arc. Without it, a take that turns back left at the end of the room blended with one
// that turns back right integrates to a heading half a turn off both, walking away from where
// either goes. Where the takes face opposite ways the shorter arc changes sides; a hysteresis of
// kTurnHysteresis keeps it from flipping back and forth, and a blend at 0 < alpha < 1 turns by
// 2 pi alpha in that one frame. Throws InputError when the shapes differ. O(F), exact.
constexpr double kTurnHysteresis = 0.78539816339744831;  // pi / 4: radians beyond pi before the arc changes sides
Eigen::MatrixXd match_turns(const Eigen::MatrixXd& steps_b, const Eigen::MatrixXd& steps_a);

}  // namespace mostyle
