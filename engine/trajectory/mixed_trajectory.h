#pragma once
// The trajectory of a mix: the stretch of the takes' common timeline it plays, its clock (each
// output frame's sample: the takes' timing mixed with the weights, mixed_clock.h, or the
// reference's) and its root path and foot contacts on the stretch's samples, from the takes' steps
// weighted as the poses are (mixed_root.h). Animation runtimes blend motion (the root) beside the
// poses the same way; mix_palette (synthesize/mix_palette.h) runs these steps around its poses.
#include <Eigen/Core>
#include <vector>

#include "engine/align/prepare_takes.h"
#include "engine/base/weighted_sum.h"
#include "engine/trajectory/weight_keys.h"
#include "engine/kinematics/sample_rows.h"
#include "engine/post/finish.h"
#include "engine/trajectory/mixed_root.h"

namespace mostyle {

// The samples of the common timeline a mix plays and what limits its foot lock.
struct PlayedStretch {
  int first = 0, last = 0;  // the stretch every take with a weight matches
  double fastest = 0.0;     // the fastest joint of those takes (the foot lock keeps the swings under it)
  Eigen::Index length() const { return last - first + 1; }
};

// A mix's clock and root, and the buffers they are made in: a mix reuses one, so that it
// allocates nothing once sized. K output frames, U samples in the stretch, N takes.
struct MixedTrajectory {
  Eigen::VectorXd u;          // K: each output frame's sample position (first..last), from output_clock
  Eigen::VectorXd u_stretch;  // K: the same counted from the stretch's first sample
  RowSampler sampler;         // u_stretch on the stretch's rows: reads anything of the stretch at the output frames
  Eigen::MatrixXd sample_w;   // keyed weights: per sample (U x N)
  Eigen::MatrixXd frame_w;    // keyed weights: per output frame (K x N)
  Eigen::MatrixXd ground_u;   // U x 2: the root's ground path, from mix_root
  Eigen::VectorXd heading_u;  // U: its heading, radians
  Eigen::MatrixXd contacts_u; // U x 2: the foot contacts, 1 planted
  Eigen::MatrixXd steps, target;  // U x 3, U x 2: the weighted steps and paths mix_root integrates
  std::vector<WeightedTerm> terms;  // the takes' columns and weights mix_root sums
  Eigen::VectorXd flips;      // U: one take's whole-turn flips
  Eigen::MatrixXd drift_u;    // (U + 1) x 2: remove_path_drift's sums
  // A root on a leash (MixParams::path_leash): the root before it (U x 2, U) and the stride map
  // (U x 4, stride_map) that fits the legs to the root kept; stride_u is empty without a leash.
  Eigen::MatrixXd free_ground_u, stride_u;
  Eigen::VectorXd free_heading_u;
  // The cycle slots the clock left out (PreparedTakes::slots, mixed_clock.h SlotPlay), in order,
  // and where each is left out: the output frame that shows the sample at its end (the frame
  // before it shows its first).
  std::vector<int> skipped;
  std::vector<Eigen::Index> skip_frames;
  std::vector<double> skip_turns;  // the weighted steps' turn over each slot left out (radians)
  Eigen::MatrixXd path_u;     // U x 2: the reference's path with the slots left out closed up (a leash)
  Eigen::VectorXd path_heading_u;  // U: its heading
  std::vector<Eigen::Index> kept;  // the stretch's rows played (all but those inside a slot left out)
  Eigen::MatrixXd played_steps;    // scratch: a matrix on the rows played, or spread back
  Eigen::VectorXd played_heading;  // scratch: the same for a heading
};

// The stretch every take with a weight matches (a take at weight 0 does not shorten it): weights,
// keys and component_weights as MixParams has them (synthesize/mix_palette.h), per_component when
// the component weights differ from `weights`, timing the weights the clock mixes. Throws
// InputError when they match no common stretch. O(N x (keys + components)).
PlayedStretch played_stretch(const PreparedTakes& p, const std::vector<double>& weights, const WeightKeys& keys,
                             const Eigen::MatrixXd& component_weights, bool per_component,
                             const std::vector<double>& timing);

// How the output's clock is weighted, as MixParams has it: by the keys where there are any, else
// by `timing` (the weights the clock mixes, as played_stretch's).
struct ClockWeights {
  const WeightKeys* keys = nullptr;             // empty: none
  const std::vector<double>* timing = nullptr;  // one per take
  bool reference_timing = false;  // by `timing` even with keys, which are read at the reference's times
  // The reference's own cycle slots only (MixParams::reference_cycles; also on the reference's
  // timing), else as many as the timing weights give (mixed_clock.h SlotPlay).
  bool reference_cycles = false;
};

// The output's clock (options as MixParams has them): s.u (K sample positions, mixed or the
// reference's), with keys each sample's
// weights (s.sample_w, U x N) and each output frame's (s.frame_w, K x N), s.u_stretch and the
// sampler on the stretch, and each take's frame at each output frame (sources). Returns the
// finish's options: a loop clip as the reference, shown whole, makes the output one loop, its
// clock landed on the loop's end (the reference's last frame, its first pose again), which the
// finish cuts off.
FinishOptions output_clock(const PreparedTakes& p, const ClockWeights& weights, const FinishOptions& options,
                           const PlayedStretch& st, MixedTrajectory& s, Eigen::MatrixXd& sources);

// The root over the stretch (s.ground_u, s.heading_u) and the contacts (s.contacts_u): steps,
// whole-turn flips and the paths pulled towards (integrate_root_towards), as the steps are
// weighted (root_w: one weight per take, or keys, with s.sample_w from output_clock; the pull as
// MixParams::root_pull_seconds), its drift from the reference's own path taken away when asked
// (remove_path_drift) and kept within `leash` body heights of it (keep_near_path;
// MixParams::path_leash, 0: free), and then facing within kPathLeashHeading of
// its heading (keep_near_heading), with the stride map from the root before the leash to the root
// kept (s.stride_u, stride_map; empty without a leash, and for a reference without gait cycles).
// On a leash, a whole loop of a reference without gait cycles travels as the reference does over
// it. Over a cycle slot the clock leaves out (s.skipped) the root neither moves nor turns, and the
// paths it is pulled towards or kept near go on from where it was left out, moved rigidly. O(U x N).
void mix_root(const PreparedTakes& p, const WeightKeys& keys, const std::vector<double>& root_w, double root_pull_seconds,
              const PathLeash& leash, const PlayedStretch& st, MixedTrajectory& s);

// Each take's frame (K x N) at the sampler's output frames; the sampler's rows count from
// sample `first`.
void write_sources(const PreparedTakes& p, const RowSampler& at, int first, Eigen::MatrixXd& sources);

}  // namespace mostyle
