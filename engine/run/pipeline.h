#pragma once
// The blend of two takes (A the reference, B the other) as the editor's pair and `blend` give it:
// one alpha (or one per component), A's and B's words. A blend is the mix of the two takes with
// weights (1 - alpha, alpha) (palette.h), in shared or paper mode (decompose_takes.h): the same
// synthesis, timing, root path and clean-up. A slider move re-runs only blend_pair, which does
// not allocate once its scratch has the right size.
#include <Eigen/Core>
#include <vector>

#include "engine/post/loop.h"
#include "engine/prepare/canonical_frame.h"
#include "engine/run/decompose_takes.h"
#include "engine/run/palette.h"
#include "engine/run/prepare_takes.h"

namespace mostyle {

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
  MixParams mix_params;
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

// The mix parameters of a blend: weights (1 - alpha, alpha), per component (1 - alpha_c,
// alpha_c) in shared mode, any alpha (how far to exaggerate is the person's call). Throws
// InputError on a non-finite alpha or a wrong count of component alphas.
MixParams blend_mix_params(const BlendParams& params, const Decomposed& decomposed);

// One blend: the mix with weights (1 - alpha, alpha), per component (1 - alpha_c, alpha_c), B's
// basic-motion core at swap_level in paper mode (mix_palette). Throws InputError on a
// non-finite alpha, a wrong count of component alphas, a bad swap level, more than two takes,
// or a loop asked of a blend without two foot strikes. Cost: mix_palette's (about 0.2 ms of
// synthesis for a minute at 30 fps with one alpha); allocation-free once `scratch` and `out`
// have the right sizes (per-component alphas and a loop allocate).
void blend_pair(const PreparedTakes& prepared, const Decomposed& decomposed, const BlendParams& params,
                BlendScratch& scratch, BlendResult& out);

// The blend's output frames in A's own clip frames (for export's A rotations): source_a scaled
// from the working rate to A's rate.
Eigen::VectorXd source_frames_in_clip(const PreparedTakes& prepared, const BlendResult& blend);

}  // namespace mostyle
