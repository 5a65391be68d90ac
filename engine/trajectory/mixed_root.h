#pragma once
// The root path of a mix: the takes' steps weighted (prepare/root_path.h), their whole-turn flips
// spread where a weight makes them visible, integrated and pulled towards the takes' own paths.
#include <Eigen/Core>

namespace mostyle {

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

// Keeps a root path (ground, F x 2) near another (path, F x 2: the content's own, for a transfer
// whose content is its own neutral) on a soft leash: where the gap between them is under
// leash / 2 the path is as it was; beyond, the gap is eased towards `leash` and never reaches it
// (r/2 + r/2 tanh((d - r/2) / (r/2)): its rate of change is continuous, so the root does not
// jump where the leash tightens). Without a neutral, the change from a content to its style is the
// whole difference of the two takes, their paths too: walking the style's path, a long take would
// end far from where its content went. Where the leash holds, the
// root goes at the content's pace while the legs take the style's steps, and the lock then has
// that difference to take up. leash <= 0: nothing. O(F), no allocation.
// Test: "cli transfer without --neutral: the content is its own neutral" (tests/app/cli/cli_synthesis_commands_test.cpp).
void keep_near_path(Eigen::MatrixXd& ground, const Eigen::Ref<const Eigen::MatrixXd>& path, double leash);

// A root on a leash drifts from the path it is kept near as the mix's steps add up (an old walk's
// shorter steps put on a longer-striding content travel less), and the leash would then hold it
// at its end, a steady gap beside the content's way. This takes that drift away before the
// leash: the gap from `path`, averaged over `window` samples centred on each (the ends: what the
// window holds), is subtracted, leaving the gap's swings within about a second (a sway, a
// lunge of the style) as they were. ground, path: F x 2 (x, z); scratch: resized to F x 2.
// window <= 1 or F < 2: nothing. O(F).
void remove_path_drift(Eigen::MatrixXd& ground, const Eigen::Ref<const Eigen::MatrixXd>& path, Eigen::Index window,
                       Eigen::MatrixXd& scratch);

// The same for a heading (F, radians) and the path's (F): the shorter arc between them eased as
// keep_near_path eases a gap. A root kept on a path faces as the path's walker does: facing where
// the style take turned while going where the content went, its legs would step sideways to the
// way it goes, and its planted feet would slide.
// Test: "palette: planted feet of a mix and a transfer move as their takes' do" (tests/engine/synthesize/mix_palette_test.cpp).
// remove_path_drift's window: longer than a gait cycle, so a stride's sway is kept.
constexpr double kPathDriftSeconds = 1.2;

// A root kept near the reference's own path (a transfer's content), as MixParams asks it.
struct PathLeash {
  double body_heights = 0.0;   // keep_near_path's leash, in body heights; 0: the mixed path as it comes
  double drift_seconds = 0.0;  // remove_path_drift's window before the leash, seconds; 0: none
  bool operator==(const PathLeash& o) const { return body_heights == o.body_heights && drift_seconds == o.drift_seconds; }
};
constexpr double kPathLeashHeading = 0.05;  // radians: the leash on a heading kept with its path
void keep_near_heading(Eigen::VectorXd& heading, const Eigen::Ref<const Eigen::VectorXd>& path, double leash);

// The stride map of a root kept on a leash (post/stride_warp.h): at each sample, the 2 x 2 map
// on the body frame's (x, z) (row-major in map's 4 columns) that fits the feet's way under the
// body to the kept root's pace, each root's travel measured in its own body frame over
// kStrideWindowSeconds about the sample (a gait cycle or so: the pace, not the sway within a
// step). For the free travel v (speed |v|, way d = v / |v|) and the kept one w it scales along d
// by 1 + min(kStrideLongerLimit, (w.d - |v|) |v| / (|v|^2 + e^2)), e kStrideStillSpeed body
// heights per second, and leaves the way across as it is: shorter steps where the kept root goes
// slower along d, longer ones (by at most kStrideLongerLimit: the legs' reach and the speed limit
// bound the rest) where it goes faster, and fading to the identity where the free root barely
// moves (a stand, a turn on the spot: no stride to fit). The scale is at least 1 -
// kStrideMapLimit: a pace far below the free root's is not a stride to fold a leg to.
// free_ground, ground: U x 2; free_heading, heading: U. Writes map (U x 4); allocation-free when
// it has that size. O(U).
constexpr double kStrideWindowSeconds = 1.0;
constexpr double kStrideStillSpeed = 0.1;
constexpr double kStrideMapLimit = 0.6;
constexpr double kStrideLongerLimit = 0.5;
void stride_map(const Eigen::MatrixXd& free_ground, const Eigen::VectorXd& free_heading, const Eigen::MatrixXd& ground,
                const Eigen::VectorXd& heading, double fps, double body_height, Eigen::MatrixXd& map);

}  // namespace mostyle
