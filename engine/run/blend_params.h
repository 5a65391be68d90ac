#pragma once
// A blend of two takes (A the reference, B the other) in the words the editor's pair and `blend`
// use: one alpha (or one per component), B's basic-motion core at a level, A's timing. A blend is
// the mix of the two takes with weights (1 - alpha, alpha) (mix_palette.h, mix_palette), in shared or
// paper mode (decompose_takes.h): the same synthesis, timing, root path and clean-up; these are
// its parameters in a mix's terms.
#include <vector>

#include "engine/decompose/decompose_takes.h"
#include "engine/synthesize/mix_palette.h"
#include "engine/trajectory/mixed_root.h"

namespace mostyle {

struct BlendParams {
  double alpha = 0.5;                    // 0: A, 1: B (shared mode)
  std::vector<double> component_alpha;   // shared mode: per component, overrides alpha; empty: none
  int swap_level = 0;                    // basic motions: the level whose core comes from B
  bool limb_lengths = true;              // paper 3.7
  double root_pull_seconds = kRootPullSeconds;  // keeps the path between A's and B's (trajectory/mixed_root.h)
  bool foot_lock = true;                 // pin planted feet after the limb lengths (post/foot_lock.h)
  // Timing (trajectory/mixed_clock.h): false blends A's and B's timing with alpha (alpha 0 plays at A's
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

// The mix parameters of a blend: weights (1 - alpha, alpha), per component (1 - alpha_c,
// alpha_c) in shared mode, any alpha (how far to exaggerate is the person's call), B's core at
// swap_level. Throws InputError on a non-finite alpha or a wrong count of component alphas.
MixParams blend_mix_params(const BlendParams& params, const Decomposed& decomposed);
// Per-component alphas as per-component mix weights into `out` (k x 2): (1 - alpha_c, alpha_c).
// Throws InputError on a non-finite alpha. No allocation once `out` is sized.
void set_component_alpha_weights(const std::vector<double>& alphas, Eigen::MatrixXd& out);
// The same into `mix`, whose vectors are reused: a slider move allocates nothing once they are
// sized.
void set_blend_mix_params(const BlendParams& params, const Decomposed& decomposed, MixParams& mix);

}  // namespace mostyle
