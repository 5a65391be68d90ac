#pragma once
// Registration by cycles (issue 16), its first part: which cycle of another take each cycle of the
// reference is matched with, and where in that take each reference frame inside a cycle falls.
// A take with fewer cycles than the reference has its cycles reused in order (its first, its
// second, ..., its last, its first again), so that its own cycle-to-cycle variation is kept and
// the reference is covered whole, however short the take. Frames of the reference outside its
// cycles (standing, a start, a stop, a turn on the spot) have no match: there the other take is
// to give its posture only.
#include <Eigen/Core>
#include <vector>

#include "engine/align/cycles.h"

namespace mostyle {

// For each cycle of the reference, the index of the take's cycle matched with it; empty when
// either has no cycles. The take's cycles are used in order from its first, then again.
std::vector<int> pair_cycles(const TakeCycles& reference, const TakeCycles& take);

// The take's frame (fractional) at each of the reference's `frames` frames: inside reference
// cycle k, the same phase of take cycle pairs[k] (linear in time within the cycle); NaN outside
// the reference's cycles. pairs: from pair_cycles. Throws InputError when pairs does not have
// one entry per reference cycle, names a cycle the take does not have, or a cycle runs past
// `frames`. O(frames).
Eigen::VectorXd frames_by_cycles(const TakeCycles& reference, const TakeCycles& take, const std::vector<int>& pairs,
                                 int frames);

}  // namespace mostyle
