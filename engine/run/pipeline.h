#pragma once
// The paper's synthesis of two takes (A the reference, B the other) prepared by prepare_takes
// (prepare_takes.h), as two cached stages:
//   decompose_pair sparse-coding decomposition (shared or paper mode, basic motions);
//   blend_pair     synthesis for one alpha, de-normalization, root trajectory, limb lengths.
// Each stage takes the previous one's immutable value. A slider move re-runs only blend_pair,
// which does not allocate once its scratch has the right size.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "engine/decompose/basic_motions.h"
#include "engine/decompose/body_parts.h"
#include "engine/prepare/canonical_frame.h"
#include "engine/io/clip.h"
#include "engine/decompose/decomposition.h"
#include "engine/align/alignment.h"
#include "engine/post/finish.h"
#include "engine/post/foot_contact.h"
#include "engine/post/loop.h"
#include "engine/io/job_control.h"
#include "engine/prepare/major_skeleton.h"
#include "engine/prepare/normalize.h"
#include "engine/run/decompose_params.h"
#include "engine/run/palette.h"
#include "engine/run/prepare_takes.h"
#include "engine/synthesize/synthesis.h"

namespace mostyle {

struct DecomposedPair {
  DecomposeParams params;
  // Shared mode: the two takes' shared components, as a palette's (palette.h); one alpha is
  // the mix with weights (1 - alpha, alpha). Per-component alphas synthesize from the weights.
  std::shared_ptr<const PaletteDecomposition> shared;
  SharedSynthesis shared_synthesis;
  // Paper mode.
  Decomposition paper_a, paper_b;
  PaperSynthesis paper_synthesis;
  BasicMotions basic_a, basic_b;
  BasicMotionSynthesis basic_synthesis;
  // Summary, file units.
  double rmse_a = 0, rmse_b = 0;
  double nonzero_a = 0, nonzero_b = 0;
  int iterations = 0;
  double elapsed_ms = 0;
  // The components' channels (3M) that are non-zero, per component (k x 3M booleans as 0/1).
  Eigen::MatrixXd support;
  // Per component: its joints, centre, body region and plain name (body_parts.h).
  std::vector<ComponentJoints> component_joints;
  int components() const { return params.components; }
};

// prepared: two takes. Throws InputError on bad parameters or more takes, or Cancelled.
std::shared_ptr<const DecomposedPair> decompose_pair(const PreparedTakes& prepared,
                                                     const DecomposeParams& params,
                                                     JobControl* control = nullptr);

struct BlendParams {
  double alpha = 0.5;                    // 0: A, 1: B (shared mode)
  std::vector<double> component_alpha;   // shared mode: per component, overrides alpha; empty: none
  int swap_level = 0;                    // basic motions: the level whose core comes from B
  bool limb_lengths = true;              // paper 3.7
  double root_pull_seconds = kRootPullSeconds;  // keeps the path between A's and B's (canonical_frame.h)
  bool foot_lock = true;                 // pin planted feet after the limb lengths (foot_contact.h)
  // Timing (align/timing.h): false blends A's and B's timing with alpha (alpha 0 plays at A's
  // timing and length, 1 at B's); true keeps A's timeline, for a blend that must stay in sync.
  bool timing_a = false;
  bool loop = false;                     // cut a seamless loop of whole gait cycles (post/loop.h)
  // Shared mode: blend each take's residual (what the k components do not hold, X - W C) with
  // the same alpha (with per-component alphas, each joint's the mean of its components'), so alpha 0 is exactly A and 1
  // exactly B, and the blend never moves faster than the faster take; off: the components'
  // reconstruction alone, as the paper's synthesis has it. Paper mode never adds residuals
  // (basic motions add A's, as the paper's chain does).
  bool residual = true;
};

// Buffers blend_pair reuses between calls so a slider move allocates nothing.
struct BlendScratch {
  Eigen::MatrixXd x, samples, ground, steps, ground_u, contacts_u;
  Eigen::VectorXd heading, heading_u, alphas, u;
  Eigen::RowVectorXd mean;
  Eigen::MatrixXd joint_alpha;  // per-component alphas: each joint's
  RowSampler sampler;  // the output frames' places on the warp
  RowSampler sampler_a, sampler_b;  // their frames in each take
  Eigen::VectorXd source_a, source_b;
  FinishScratch finish;
  FinishedMotion finished;
  MixParams mix_params;  // one alpha in shared mode: the mix of two (palette.h)
  MixScratch mix_scratch;
  MixResult mix;
};

struct BlendResult {
  Eigen::MatrixXd world;            // K x 3M: the blend in A's world frame, A's units, K output frames
  Eigen::VectorXd source_a;         // K: A's frame (fractional, working rate) each output frame shows
  Eigen::VectorXd source_b;         // K: B's frame
  Eigen::VectorXd sample;           // K: the warp sample (fractional) each output frame is at
  Eigen::MatrixXd local;            // K x 3M: the blend's canonical poses (before root and clean-up)
  double limb_length_max_error = 0; // after the constraint (before it when off), A's units
  Eigen::MatrixXd contacts;         // K x 2: the blend's foot contacts (A's and B's blended)
  double foot_sliding_raw = 0;      // foot sliding before the foot lock, A's units per second
  double foot_sliding_cleaned = 0;  // after it (the same as raw when the lock is off)
  LoopCut loop;                     // with BlendParams::loop: where the loop was cut (output frames before the cut)
  double synthesize_ms = 0, postprocess_ms = 0;
};

// Synthesizes one blend (paper 3.6) on the warp's samples, plays it along the blended timeline
// and post-processes it (de-normalize, blended root trajectory from A's start, limb lengths,
// foot lock, and the loop when asked). Throws InputError on a bad alpha or swap level, or a loop
// asked of a blend without two foot strikes. Cost O((U + K) x 3M) in shared mode with one alpha
// (about 0.5 ms for a minute at 30 fps), else O(U x k x 3M); allocation-free once `scratch`
// and `out` have the right sizes (per-component alphas allocate one 2k x 3M matrix, a loop
// allocates).
void blend_pair(const PreparedTakes& prepared, const DecomposedPair& decomposed,
                const BlendParams& params, BlendScratch& scratch, BlendResult& out);

// The blend's output frames in A's own clip frames (for export's A rotations): source_a scaled
// from the working rate to A's rate.
Eigen::VectorXd source_frames_in_clip(const PreparedTakes& prepared, const BlendResult& blend);

}  // namespace mostyle
