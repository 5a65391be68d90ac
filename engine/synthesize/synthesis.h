#pragma once
// Motion synthesis (paper 3.6) from decompositions X = W C: the paper's core-component blend,
// the paper's basic-motion core swap. (Shared components blend their weights in mix_palette,
// engine/synthesize/mix_palette.h.)
// Each mode has a prepare_* step run once per decomposition (pair), whose motions the
// decomposition keeps (decompose/core_components.h), and a synthesize_* step run per slider
// move; the latter writes into a caller-owned output so it need not allocate.
#include <Eigen/Core>
#include <vector>

#include "engine/decompose/core_components.h"

namespace mostyle {

// Paper mode: X_syn = W_A ((1 - alpha) K_A + alpha K_B) V_A^T (PaperSynthesis). Paper mode,
// basic motions: one level's core blended (BasicMotionSynthesis).
// Every mode is linear in alpha, so prepare_* forms the two (or m + 1) frames x 3N motions the
// blend moves between, and a slider move is one pass over frames x 3N, several times cheaper
// than even one frames x k by k x 3N product. Memory: a few frames x 3N matrices per prepared
// pair. Bench: BM_SynthesizePaper (tests/bench/decomposition_bench.cpp).

// out: resized to frames x 3N (no allocation when it already has that size). alpha is usually
// in [0, 1]; values outside extrapolate. Throws InputError on a non-finite alpha.
// Cost: one pass over frames x 3N, no allocation.
void synthesize_paper(const PaperSynthesis& p, double alpha, Eigen::MatrixXd& out);
Eigen::MatrixXd synthesize_paper(const PaperSynthesis& p, double alpha);

// swap: the level (0-based) whose core is taken from B. out: resized to frames x 3N.
// Throws InputError when swap is out of range or alpha is not finite.
// Cost: one pass over frames x 3N, no allocation.
void synthesize_basic_motions(const BasicMotionSynthesis& p, int swap, double alpha,
                              Eigen::MatrixXd& out);
Eigen::MatrixXd synthesize_basic_motions(const BasicMotionSynthesis& p, int swap, double alpha);

}  // namespace mostyle
