#pragma once
// The synthesis, the last stage of the one chain: the takes prepared by
// prepare_takes and decomposed by decompose_takes, mixed as layers (mix_layers.h: a weight per
// take, or per component, and additive layers): poses, timing, root path and foot contacts mixed
// with the takes' weights, then the clean-up (post/finish.h). Shared mode mixes the takes'
// component weights (any number of takes); paper mode (two takes) is the paper's synthesis with
// alpha the second take's weight. A blend of two takes at alpha is the mix of two layers
// (1 - alpha, alpha); a transfer (a style put on a take of one's own) is a mix whose reference
// is the content take, its layer at 1 and each style an additive layer (transfer_layers).
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "engine/align/common_timeline.h"
#include "engine/align/prepare_takes.h"
#include "engine/base/weighted_sum.h"
#include "engine/trajectory/weight_keys.h"
#include "engine/decompose/body_parts.h"
#include "engine/decompose/decompose_takes.h"
#include "engine/decompose/decomposition.h"
#include "engine/post/finish.h"
#include "engine/synthesize/mix_layers.h"
#include "engine/trajectory/mixed_root.h"
#include "engine/trajectory/mixed_trajectory.h"

namespace mostyle {

constexpr double kMinMixWeight = -0.5;  // mild exaggeration away from a take
constexpr double kMaxMixWeight = 1.5;   // mild exaggeration beyond a take

// Weights typed as decimals may miss 1 by their rounding (six times 0.166667 is 1.000002): a sum
// within this of 1 is taken as meant.
constexpr double kTypedWeightSumTolerance = 1e-3;
// `typed` divided by its sum when that is within kTypedWeightSumTolerance of 1, so that the
// weights sum to 1 as MixParams::Validate asks; as typed otherwise, for Validate to refuse.
std::vector<double> normalized_weights(const std::vector<double>& typed);

struct MixParams {
  // The layers (mix_layers.h): each take's weight the sum of theirs, summing to 1; per component
  // when a layer has weights per component (from per-part weights: part_weights).
  MixLayers layers;
  // Weights keyed in time (weight_keys.h; each key one weight per take, as take_weights gives
  // them); non-empty: they replace the layers' over the output (shared mode, the whole body: no
  // layer with weights per component).
  WeightKeys keys;
  // The range each take's weight (whole body, per component, in each key) must be in: one rule
  // for any number of takes; transfers allow more.
  double min_weight = kMinMixWeight, max_weight = kMaxMixWeight;
  int swap_level = 0;                // paper mode with basic motions: the level whose core comes from take 1
  bool reference_timing = false;     // keep the reference's timeline instead of mixing timing
  // Shared mode: mix each take's residual (what the k components do not hold, X - W C) with the
  // same weights (per component, each joint's the mean of its components'), so that a take's
  // whole weight gives exactly that take; off: the components' reconstruction alone, as the
  // paper's synthesis has it. Paper mode never adds residuals (basic motions add the first
  // take's, as the paper's chain does).
  bool residual = true;
  double root_pull_seconds = kRootPullSeconds;
  // A transfer: the output's planted feet are held to the reference take's own (the content's
  // planted speed and drift), whatever the weights; else to the takes' mixed by weight.
  bool feet_of_reference = false;
  // A transfer: the output plays the reference's own cycles (the content's), none of the slots a
  // style take with more cycles adds (PreparedTakes::slots); else as many as the timing weights
  // give (a blend at a take's weight 1 plays its cycles). The reference's timing plays its own.
  bool reference_cycles = false;
  // The root kept near the reference's own path (trajectory/mixed_root.h PathLeash); none: the
  // mixed path as it comes. A transfer takes transfer_path_leash.
  PathLeash path_leash;
  FinishOptions finish;              // limb lengths, foot lock, loop
  // A preview: the poses, the root and the limb lengths only (finish.h finish_preview), without
  // the speed limit, the foot lock and the measures (MixResult::motion's foot_sliding_raw,
  // _cleaned and limb_length_max_error 0); finish_mix_palette completes it.
  bool preview = false;
  // Throws InputError, in one sentence, on a layer of a take that is not one of `takes`, weights
  // per component that are not `components`, a non-finite weight, a take's weight outside
  // [min_weight, max_weight] or weights that do not sum to 1 (whole body, per component, in a key).
  void Validate(int takes, int components) const;
};

struct MixScratch {
  Eigen::MatrixXd x, samples, joint_weights, stretch, local_t, component_w;
  // A transfer's change at each output frame, its mean, and per joint the content's and the
  // neutral's movement and the share of the change's movement left out (still_where_content_is).
  Eigen::MatrixXd change;
  Eigen::RowVectorXd change_mean;
  Eigen::VectorXd amp_content, amp_from, left_out;
  Eigen::VectorXd channel_mean, channel_spread;  // joint_amplitudes' per channel, over a take's frames
  Eigen::MatrixXd drift;              // K x 2 kFootJoints: the planted feet's expected moves (the foot lock's)
  Eigen::MatrixXd feet_height;        // K x kFootJoints: the takes' foot joints' heights, planted bands (feet_heights)
  std::vector<double> heights;        // one take's joint's heights at the frames shown, twice (feet_heights)
  Eigen::RowVectorXd channel_w, mixed_mean;
  std::vector<WeightedTerm> terms;    // one output frame's takes' frames and their weights (own_poses)
  std::vector<double> weights;        // each take's, from the layers (take_weights)
  Eigen::MatrixXd part_w;             // k x N per component, from the layers; empty: none
  std::vector<double> overall, timing, drift_w;
  MixedTrajectory trajectory;         // the clock, the root and the contacts (trajectory/mixed_trajectory.h)
  FinishScratch finish;
  Eigen::MatrixXd sources_uncut;  // a loop's MixResult::sources before the cut, for the planted drift
  Eigen::MatrixXd stride;         // K x 4: a leashed root's stride map at the output frames (stride_warp.h)
  // What a preview mix leaves for finish_mix_palette.
  struct Pending {
    bool waiting = false;   // a preview not finished yet
    FinishOptions options;  // the finish's options (a loop clip's closed, ...)
    double fastest = 0.0;   // the weighted takes' fastest joint
  } pending;
};

struct MixResult {
  FinishedMotion motion;     // world (K x 3M, the reference's units and world), contacts, loop, ...
  Eigen::MatrixXd local;     // K x 3M canonical poses before the root and the clean-up (a leashed root's strides fitted)
  Eigen::VectorXd sample;    // K: the common timeline's sample each output frame is at
  int first_sample = 0, last_sample = 0;  // the stretch played: where every take with a weight is matched
  Eigen::MatrixXd sources;   // K x N: each take's frame (fractional, working rate) at each output frame
  // Where the clock left a cycle slot out (PreparedTakes::slots): the output frames after each,
  // from which the poses' jump there is eased out over slot_ease frames (a cycle).
  std::vector<Eigen::Index> slot_skips;
  Eigen::Index slot_ease = 0;
  // How fast the takes' own planted feet move (PreparedTake::planted), weighted as mixed (with
  // keys, each take's mean weight over the output; per part, its mean over the components): what
  // motion.foot_sliding_raw and _cleaned are measured against. With a negative weight (a
  // transfer's neutral take, an exaggeration) no blend of the takes is walked: the reference
  // take's own (a transfer's content). File units per second.
  double foot_sliding_inputs = 0.0;
  // The fastest joint of the takes mixed (those with a weight), file units per second: what
  // motion.fastest_joint is held under (no pops).
  double fastest_inputs = 0.0;
};

// One mix (see the top of this file). Throws InputError from params.Validate, a loop without
// two foot strikes, or keys in paper mode. One weight set: the poses at the output frames only, O(K x N x 3M), and the
// root on the samples, O(U x N); per-component weights add O(U x k x (3M + N)).
// Allocation-free once scratch and out are sized (per-component weights, keys and a loop allocate).
// With keys, each output frame's pose takes the keys' weights at its time, and the root, contacts
// and timing each sample's (trajectory/mixed_clock.h mixed_timeline with keys): O(K x N x 3M + U x N) as above.
// times: when given, its synthesize_ms (the poses) and postprocess_ms (root, clean-up) are set.
void mix_palette(const PreparedTakes& palette, const Decomposed& decomposition, const MixParams& params,
                 MixScratch& scratch, MixResult& out, StageTimes* times = nullptr);

// Completes a preview (MixParams::preview) in out: the speed limit, the foot lock and the
// measures, as mix_palette without preview would have run them; the preview then this give
// exactly mix_palette's result without preview. p and params as the preview had them, scratch
// and out as it left them. Does nothing when the last mix_palette with this scratch was not a
// preview or has been completed. O(K x M), the foot lock's several tries most of it; allocates
// nothing once sized (a loop copies its sources). times: when given, its postprocess_ms grows by
// the time taken.
void finish_mix_palette(const PreparedTakes& palette, const MixParams& params, MixScratch& scratch, MixResult& out,
                        StageTimes* times = nullptr);

// Per-component weights (k x N) from weights given per body part: each component takes the
// row of the part that decides its region (body_parts.h deciding_part), else `rest`. Throws
// InputError when a row is not N weights.
Eigen::MatrixXd part_weights(const std::vector<std::pair<BodyPart, std::vector<double>>>& given,
                             const std::vector<ComponentJoints>& components, const std::vector<double>& rest);

// A transfer's MixParams::path_leash. A content that is its own neutral keeps its path, within a
// fifth of the body's height, facing as it does (trajectory/mixed_root.h): its change is
// everything between two takes, the style take's walk too (another direction and pace). So does
// a content on its own timing (content_timing: MixParams::reference_timing) styled from a neutral
// take, its drift from the content's path taken away first (remove_path_drift): the style's change
// of stride length would otherwise cut the content's travel and turns, and the leash alone would
// hold the root at its end. Only a transfer from a neutral take on the mixed timing walks the
// style's change of path (an old walk's shorter steps), as it takes its pace. The strides are
// fitted to the pace kept (post/stride_warp.h).
constexpr double kOwnNeutralPathLeash = 0.2;
constexpr PathLeash transfer_path_leash(TransferNeutral neutral, bool content_timing) {
  if (neutral == TransferNeutral::kContent) return PathLeash{kOwnNeutralPathLeash, 0.0};
  if (content_timing) return PathLeash{kOwnNeutralPathLeash, kPathDriftSeconds};
  return PathLeash{};
}
// The range a transfer's weights of `styles` styles take (MixParams::min_weight, max_weight):
// the neutral's (or the content's, when it is its own neutral) down to -kMaxStrength per style,
// up to the larger of a style's kMaxStrength (the content's 1 beside it) and 1 - kMinStrength per
// style (the content's own when every strength is negative).
constexpr double transfer_min_weight(int styles) { return -kMaxStrength * styles; }
constexpr double transfer_max_weight(int styles) {
  return kMaxStrength + 1.0 > 1.0 - kMinStrength * styles ? kMaxStrength + 1.0 : 1.0 - kMinStrength * styles;
}

// The output frames in the reference's own clip frames (its rotations at fractional frames), for
// export (with prepare_takes.h export_joints).
Eigen::VectorXd source_frames_in_clip(const PreparedTakes& palette, const MixResult& mix);

}  // namespace mostyle
