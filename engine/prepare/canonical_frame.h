#pragma once
// The canonical frame: joint positions relative to the hips' ground projection in
// the body's own heading frame, with the root trajectory kept apart so it can be blended and
// placed back in any world frame. Y is up (other up axes are rotated to Y before).
#include <Eigen/Core>

namespace mostyle {

// One take in the canonical frame. F frames, J joints.
struct CanonicalMotion {
  Eigen::MatrixXd local;    // F x 3J: R_y(-heading) (p - ground), file units
  Eigen::MatrixXd ground;   // F x 2: the hips' ground projection (x, z), world, file units
  Eigen::VectorXd heading;  // F: radians about +Y, 0 facing +Z, unwrapped (continuous)
};

// world: F x 3J positions; hips, left_hip, right_hip: joint indices. The heading is the direction
// perpendicular to the left-right hip axis on the ground. Throws InputError on a degenerate hip
// axis in every frame; frames where it is momentarily degenerate keep the previous heading.
CanonicalMotion to_canonical(const Eigen::MatrixXd& world, int hips, int left_hip, int right_hip);

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

// Adds weight times a take's whole-turn flips (U: match_turns's change of its turn channel, 0
// where none) to mixed steps' turns (U x 3), each flip spread over 2h + 1 samples, h growing to
// half a second at weight 1/2: at weights 0 and 1 a whole turn is invisible, in between a flip in
// one frame would turn the body by 2 pi weight at once (for weights outside [0, 1], h follows
// the weight's fraction: 1.5 turns by half a turn). O(U + flips x h), no allocation.
void add_spread_turns(const Eigen::VectorXd& flips, double weight, double fps, Eigen::MatrixXd& steps);
// The same with the weight given per sample (U values: weights keyed in time), each flip spread
// as its sample's weight says.
void add_spread_turns(const Eigen::VectorXd& flips, const Eigen::VectorXd& weights, double fps, Eigen::MatrixXd& steps);

// The root trajectory of a mix (steps: F x 3, the takes' steps weighted after match_turns),
// integrated as integrate_root does from target's first row, each step then pulled towards the
// path `target` (F x 2: the takes' own paths, weighted the same way) by the fraction
// 1 - exp(-1 / (fps * pull_seconds)) of the gap. Integrated steps alone drift apart from every
// take wherever their turns are not aligned in time (the alignment matches steps, not turns),
// so that a mix would not lie between the takes; the pull keeps it there while moving as the
// weighted steps say, up to a correction (a slide of the feet) as fast as the takes' paths part,
// spread over pull_seconds: slight for takes on similar paths, a few tenths of the body height
// per second for a straight walk mixed with one that turns back. A take alone (weight 1) gives
// its own path (the pull has nothing to correct). pull_seconds <= 0: no pull (integrate_root).
// Writes ground (F x 2) and heading (F); allocation-free when they have that size. O(F).
constexpr double kRootPullSeconds = 2.0;
void integrate_root_towards(const Eigen::MatrixXd& steps, const Eigen::MatrixXd& target, double start_heading,
                            double fps, double pull_seconds, Eigen::MatrixXd* ground, Eigen::VectorXd* heading);

// Take B's root path moved rigidly so that at B's (fractional) frame b_frame it stands where A
// stands at a_frame and faces where A faces: both then walk from one place. Ground: B's frames x 2,
// heading: B's frames.
struct PlacedRoot {
  Eigen::MatrixXd ground;
  Eigen::VectorXd heading;
};
PlacedRoot place_at(const CanonicalMotion& a, double a_frame, const CanonicalMotion& b, double b_frame);

// Places local poses (F x 3J) in the world: p = ground + R_y(heading) local. Writes into `world`
// (resized to F x 3J).
void to_world(const Eigen::MatrixXd& local, const Eigen::MatrixXd& ground,
              const Eigen::VectorXd& heading, Eigen::MatrixXd* world);

}  // namespace mostyle
