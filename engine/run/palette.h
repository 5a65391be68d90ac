#pragma once
// The style palette (issue #9): any number of takes (2 to 16, prepared by prepare_takes,
// prepare_takes.h) mixed with weights, as two cached stages, each an immutable value built from
// the one before:
//   decompose_palette  one shared, local decomposition of the stacked takes (W_i per take, C);
//   mix_palette        one mix for a set of weights: poses, timing, root path and foot contacts
//                      mixed with the weights, then the pair's clean-up (post/finish.h).
// Two takes with weights (1 - a, a) give blend_pair's shared-mode blend at alpha a, frame for
// frame. A transfer (a style put on a take of one's own) is a mix whose reference is the content
// take, with weights (1, -s, s) on content, neutral and style (transfer_weights).
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "engine/align/common_timeline.h"
#include "engine/decompose/body_parts.h"
#include "engine/decompose/decomposition.h"
#include "engine/post/finish.h"
#include "engine/run/decompose_params.h"
#include "engine/run/prepare_takes.h"

namespace mostyle {

constexpr double kMinMixWeight = -0.5;  // mild exaggeration away from a take
constexpr double kMaxMixWeight = 1.5;   // mild exaggeration beyond a take

// The stacked decomposition's components are fitted on at most this many frames (every take's
// samples at a stride): eight one-minute takes are 23 000 samples, and the components (body
// parts' shapes) need no more than a few per gait phase. The weights of every sample are then
// the least-squares fit to those components.
constexpr int kMaxDecompositionFrames = 6000;

struct PaletteDecomposition {
  DecomposeParams params;          // shared mode (local unless params.local is off)
  StackedDecomposition stacked;    // W_i and C
  // Per take, A's units, U x 3M: the components' reconstruction W_i C de-normalized, and the
  // residual (what the components do not hold). Their sum is the take's pose exactly.
  std::vector<Eigen::MatrixXd> reconstructed, residual;
  std::vector<double> rmse;        // per take, file units
  int stride = 1;                  // the components were fitted on every stride-th sample
  Eigen::MatrixXd support;         // k x 3M, 1 where a component is non-zero
  std::vector<ComponentJoints> component_joints;
  double elapsed_ms = 0;
  int components() const { return params.components; }
};

// Throws InputError on bad parameters (paper mode and basic motions are the pair's), Cancelled.
// Cost: decompose() on N x U frames, then N U x k by k x 3M products.
std::shared_ptr<const PaletteDecomposition> decompose_palette(const PreparedTakes& palette,
                                                              const DecomposeParams& params,
                                                              JobControl* control = nullptr);

// Weights typed as decimals may miss 1 by their rounding (six times 0.166667 is 1.000002): a sum
// within this of 1 is taken as meant.
constexpr double kTypedWeightSumTolerance = 1e-3;
// `typed` divided by its sum when that is within kTypedWeightSumTolerance of 1, so that the
// weights sum to 1 as MixParams::Validate asks; as typed otherwise, for Validate to refuse.
std::vector<double> normalized_weights(const std::vector<double>& typed);

struct MixParams {
  std::vector<double> weights;       // one per take, summing to 1
  // Per component, one weight per take (k x N, each row summing to 1), from per-part weights
  // (part_weights); empty: `weights` for every component.
  Eigen::MatrixXd component_weights;
  double min_weight = kMinMixWeight, max_weight = kMaxMixWeight;  // transfers allow more
  bool reference_timing = false;     // keep the reference's timeline instead of mixing timing
  bool residual = true;              // mix each take's residual too (BlendParams::residual)
  double root_pull_seconds = kRootPullSeconds;
  FinishOptions finish;              // limb lengths, foot lock, loop
  // Throws InputError, in one sentence, on a weight count that is not `takes`, a non-finite
  // weight, a weight outside [min_weight, max_weight] or weights that do not sum to 1.
  void Validate(int takes, int components) const;
};

struct MixScratch {
  Eigen::MatrixXd samples, steps, ground_u, target, contacts_u, joint_weights, stretch, local_t;
  Eigen::VectorXd heading_u, u, u_stretch, flips;
  std::vector<double> overall, timing;
  RowSampler sampler;
  FinishScratch finish;
};

struct MixResult {
  FinishedMotion motion;     // world (K x 3M, the reference's units and world), contacts, loop, ...
  Eigen::MatrixXd local;     // K x 3M canonical poses before the root and the clean-up
  Eigen::VectorXd sample;    // K: the common timeline's sample each output frame is at
  int first_sample = 0, last_sample = 0;  // the stretch played: where every take with a weight is matched
  Eigen::MatrixXd sources;   // K x N: each take's frame (fractional, working rate) at each output frame
  double synthesize_ms = 0, postprocess_ms = 0;
};

// One mix (see the top of this file). Throws InputError from params.Validate or a loop without
// two foot strikes. One weight set: the poses at the output frames only, O(K x N x 3M), and the
// root on the samples, O(U x N); per-component weights add O(U x k x (3M + N)).
// Allocation-free once scratch and out are sized (per-component weights and a loop allocate).
void mix_palette(const PreparedTakes& palette, const PaletteDecomposition& decomposition, const MixParams& params,
                 MixScratch& scratch, MixResult& out);

// Per-component weights (k x N) from weights given per body part: each component takes the
// row of the part that decides its region (body_parts.h deciding_part), else `rest`. Throws
// InputError when a row is not N weights.
Eigen::MatrixXd part_weights(const std::vector<std::pair<BodyPart, std::vector<double>>>& given,
                             const std::vector<ComponentJoints>& components, const std::vector<double>& rest);

// A transfer's weights on takes [content, neutral, style_1, ..., style_n]: content 1, neutral
// -sum s_i, style i s_i. Throws InputError on no style or a strength outside [kMinStrength,
// kMaxStrength].
constexpr double kMinStrength = -1.0;
constexpr double kMaxStrength = 2.0;
std::vector<double> transfer_weights(const std::vector<double>& strengths);

// The reference's joint index of each major column (for export), and the output frames in the
// reference's own clip frames (its rotations at fractional frames).
std::vector<int> export_joints(const PreparedTakes& palette);
Eigen::VectorXd source_frames_in_clip(const PreparedTakes& palette, const MixResult& mix);

}  // namespace mostyle
