#pragma once
// Timing mixed with the weights (timing is part of style; after Kovar and Gleicher's registration
// curves, 2003): along the takes' common timeline the output advances at the weighted sum of the
// takes' rates, so a take alone plays at its own timing and length. Where one take advances
// faster than another, the output's velocity is then a weighted mean of the takes' own
// velocities, never faster than the fastest of them.
#include <Eigen/Core>

#include <vector>

#include "engine/align/common_timeline.h"
#include "engine/align/cycle_slots.h"
#include "engine/trajectory/weight_keys.h"

namespace mostyle {

// Samples first..last of the takes' common timeline, both included.
struct SampleSpan {
  int first = 0, last = 0;
};

// The cycle slots a mix plays (cycle_slots.h). While the reference has a weight, its own cycles
// all play (all of it at every weight below 1), and of the slots it plays again those the other
// takes' weights call for (SlotCount: a blend of a walk of 5 cycles with one of 7 plays 6 half
// way); at the reference's weight 0, as many slots as the weights give the takes' own cycles, so
// that a take at weight 1 plays its own cycles once each. A slot not played gets no time on the
// clock: the output leaves it out, from its first sample straight to its last. A slot the
// stretch cuts is always played.
struct SlotPlay {
  const CycleSlots* slots = nullptr;    // none: every sample plays
  bool reference_only = false;          // the reference's own slots whatever the weights (a transfer's content)
  std::vector<int>* skipped = nullptr;  // when given: set to the slots left out, in order
};

// Where the mixed clock ends: T(last) (output frames, fractional) and the first sample from which
// it no longer advances up to `last` (a reference held at its last frame while another take's rest
// plays gets no time there on the reference's clock: its last frame is that sample, not `last`).
struct ClockEnd {
  double clock = 0.0;
  int sample = 0;
};

// Output frame k sits where the mixed clock T reaches k, over the span first..last of the takes'
// common timeline: T(first) = 0 and T advances by sum_i w_i times take i's frames from one sample
// to the next (weights: one per take, summing to 1; negative ones exaggerate), but never less than
// the slowest weighted take advances, so that negative weights cannot stall the clock; T is linear
// between samples. Writes each output frame's fractional sample position (first..last) into u
// (floor(T(last)) + 1 frames; no allocation when it has that size) and, when `end` is given,
// where the clock ends (ClockEnd). Two takes with weights
// (1 - w, w) on a one-warp timeline play at A's timing and length for w = 0 and at B's for w = 1.
// Throws InputError on a weight count that is not the takes', a non-finite weight, or an empty
// or out-of-range stretch. O((last - first) x N + frames).
// slots: the cycle slots to play (SlotPlay), none by default.
void mixed_timeline(const CommonTimeline& timeline, const std::vector<double>& weights, SampleSpan span,
                    Eigen::VectorXd& u, ClockEnd* end = nullptr, const SlotPlay& slots = {});

// The same with the weights keyed in time (weight_keys.h, validated for the timeline's takes):
// the clock's advance from sample k - 1 to k takes the keys' weights at the output time the clock
// has reached at k - 1 (seconds = clock / fps), so the timing changes as the weights do and the
// keys' times are seconds of the output. sample_weights: when given, set to the weights at each
// sample's output time ((last - first + 1) x N), for the root and contacts. Throws as the above.
// O((last - first) x N + frames); allocates.
// Each slot is decided by the keys' weights at the output time the clock has reached at its first sample.
void mixed_timeline(const CommonTimeline& timeline, const WeightKeys& keys, double fps, SampleSpan span,
                    Eigen::VectorXd& u, Eigen::MatrixXd* sample_weights = nullptr, ClockEnd* end = nullptr,
                    const SlotPlay& slots = {});

// Output frames (u: K sample positions, increasing, from mixed_timeline) retimed so that the last
// lands exactly on sample `last` (where the clock ends, ClockEnd::sample): a whole loop (its last
// sample repeats its first pose) then ends on a frame, to be cut off as the loop closes. The
// clock's end, clock_at_last (ClockEnd::clock, a fraction of a frame past u's last), is rounded to a whole number of frames and the
// clock stretched or squeezed evenly to it (by at most half a frame in all); between u's last
// frame and `last` the clock runs linearly. Read from the clock, not from u's last step carried
// on: samples are not evenly spread in time (the reference's whole frames are among them), so a
// last step carried on could end a frame off and the loop's seam then step by twice a frame. u
// keeps at least two frames. O(K); allocates.
void land_on_last(Eigen::VectorXd& u, double last, double clock_at_last);

}  // namespace mostyle
