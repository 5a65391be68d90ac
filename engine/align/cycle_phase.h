#pragma once
// Cycles ready to be registered with a reference's: a loop clip read across its end, and a take's
// cycles moved to begin at the phase of the gait the reference's cycles begin at.
//
// The reference's gait cycles begin at its foot's strikes, except a loop clip's one cycle, which
// begins where the clip begins (its strike somewhere inside, TakeCycles::strike_phase). Another
// take registered onto it must have its cycles begin at the same phase of its own gait, so that
// the same foot lands at the same moment: a cycle whose strike lies at phase p of it, moved by
// (p - reference phase) of its length. A loop take has no end to run out of: it is unrolled
// (repeated, its root walking on), so a window of one cycle can begin anywhere in it.
#include <Eigen/Core>

#include "engine/align/cycles.h"
#include "engine/prepare/canonical_frame.h"

namespace mostyle {

// A loop take repeated: frame f shows frame f mod L of the loop (L = cycles.loop_frames), its
// root walking on by the loop's own steps (the step from its last frame to the next repeat's
// first is the step before it when L is the whole take). repeats >= 1.
struct UnrolledLoop {
  CanonicalMotion motion;    // repeats x L frames
  Eigen::MatrixXd contacts;  // repeats x L x 2
  int loop_frames = 0;       // L
};

// take: canonical motion (F frames), contacts F x 2; loop_frames: L, F - 1 or F. Throws InputError
// when L is not F - 1 or F (at least 2), or repeats < 1. O(repeats x L x 3M).
UnrolledLoop unroll_loop(const CanonicalMotion& take, const Eigen::MatrixXd& contacts, int loop_frames, int repeats);

// The take's cycles moved to begin at `phase` of its gait (the fraction of a cycle before its
// foot strikes, i.e. the reference's strike_phase): each cycle begins at its strike minus phase
// of its length. Cycles that meet stay meeting. A moved cycle that would leave the take's frames
// [0, frames - 1) is moved one cycle on instead when that fits, else dropped. take: gait cycles
// (strikes at take.strike_phase of each). The result's strike_phase is `phase`. O(cycles).
TakeCycles cycles_at_phase(const TakeCycles& take, double phase, int frames);

}  // namespace mostyle
