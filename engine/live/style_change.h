#pragma once
// What a style changes in a walk, as a function of the gait's phase, on a stream's bones: the
// live styler's table (live_style.h), made once from a neutral take and styled takes prepared
// with the neutral as the reference (align/prepare_takes.h: each style registered onto the
// neutral's cycles, cycle_registration.h).
//
// For each phase of the neutral's gait cycle (from a strike of its cycle foot to the next; phases
// matched by foot: in each cycle the other foot strikes at the neutral's mean phase, time linear
// on either side), the style's canonical pose (canonical_frame.h: hips-relative, heading removed)
// minus the neutral's at that phase of each of the neutral's cycles, the style's frame the one
// the alignment matched with the neutral's (its registered cycle there, a smooth warp inside it:
// alignment.h align_by_cycles), averaged over the cycles; made periodic (what a cycle's end and
// its start differ by spread over it) and lightly smoothed. Where a stream is not in a cycle, the posture change: the style's mean pose
// over its cycles minus the neutral's, what offline registration gives between cycles. Both on the
// stream's bones: each take retargeted onto them as a transfer retargets its neutral and style
// onto its content (prepare/retarget.h: scaled by leg length, the stream's joint-group shapes,
// its bone lengths), so a transfer's change and this one are made alike.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "engine/align/prepare_takes.h"

namespace mostyle {

// Rows of phases, columns of channels (x, y, z per joint), a phase a contiguous row.
using PhaseTable = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct StyleChangeOptions {
  int phases = 128;  // rows of each table: phase p / phases, p = 0 .. phases - 1
  void Validate() const;  // throws InputError on fewer than 8 or more than 4096 phases
};

struct StyleChange {
  // Per style (the prepared takes after the neutral, in order): phases x 3M, the change at each
  // phase (canonical frame, the stream's bones and units, Y up).
  std::vector<PhaseTable> cycle;
  // Per style: 1 x 3M, the posture change (between cycles).
  std::vector<Eigen::RowVectorXd> posture;
  // Per style and foot (left, right): 1 x 3M, the cycle's change averaged over the phases that
  // foot is planted in the neutral's cycles (what a planted foot is held at).
  std::vector<std::array<Eigen::RowVectorXd, 2>> planted;
  // Per foot: phases values, the share of the neutral's cycles in which it is planted there.
  std::array<Eigen::VectorXd, 2> stance;
  int cycle_foot = 0;               // the neutral's cycles begin at this foot's strikes (0 left)
  double other_strike_phase = 0.5;  // where the other foot strikes in them, on average
  double period_s = 1.0;            // the neutral's median cycle, seconds
  std::array<double, 2> stance_share{{0.6, 0.6}};  // the share of a cycle each foot is planted
  int phases() const { return cycle.empty() ? 0 : static_cast<int>(cycle.front().rows()); }
};

// prepared: [neutral, style_1, ..., style_n] prepared with the neutral as the reference;
// stream_rest: 1 x 3M, the stream skeleton's rest pose at prepared.majors (kinematics.h
// rest_positions): its bone lengths and joint-group shapes. Throws InputError in one sentence
// naming the take when the neutral has no gait cycles or a style could not be registered onto
// them by cycles (its reason). Cost: O((F_neutral + F_styles) x M) for the retargeting, O(phases x
// cycles x M) for the tables.
StyleChange style_change(const PreparedTakes& prepared, const Eigen::RowVectorXd& stream_rest,
                         const StyleChangeOptions& options = {});

}  // namespace mostyle
