#pragma once
// The gait phase of a stream, frame by frame, with no future frames (the live styler's,
// live_style.h). The phase runs over one cycle of the neutral take's gait, from a strike of its
// cycle foot (cycles.h TakeCycles::foot) to the next, with its other foot striking at
// other_strike_phase. From the stream's own strikes so far (live_feet.h):
//   - at a strike of the cycle foot the phase is 0, and runs on at one cycle per the length of
//     the cycle before (the stream's last whole cycle);
//   - at a strike of the other foot it is other_strike_phase (phases matched by foot), and runs on
//     to reach 1 where the next strike of the cycle foot is expected.
// The phase shown moves towards that prediction a little faster or slower than the prediction
// itself (never backwards, never jumping), closing an error within correction_seconds when it is
// small.
// The stream is in a cycle (its gait repeating as a walk does, as cycles.h tells offline) from a
// strike of the cycle foot that ends a cycle passing the offline checks (its length within the
// gait's range and within max_change of the stream's recent cycles, the other foot striking
// inside it in step, each foot reaching min_stride against the body), from a strike of the
// other foot in step after a strike of the cycle foot, or from the first step after standing (a
// strike of a foot that reached min_stride, none of that foot within the gait's longest cycle);
// it is out of one (standing, turning on the spot) after a cycle that fails the checks, when
// the cycle foot has not struck for 1 + max_change of the expected cycle, or when a step is
// missed (no strike of either foot for missed_step times the step expected since the last: a
// foot that drags, a stumble, where the offline cycles fail their checks and a transfer gives
// the posture). The cycle weight eases between
// 0 (out) and 1 (in) over fade_cycles of a cycle, as offline registration fades a take's own
// frames into its posture (cycle_registration.h).
#include <Eigen/Core>
#include <array>

#include "engine/align/cycles.h"

namespace mostyle {

struct LivePhaseOptions {
  double fps = 30.0;
  double leg_length = 1.0;          // file units: strides are judged by it
  int cycle_foot = 0;               // 0 left, 1 right: the foot whose strikes begin a cycle
  double other_strike_phase = 0.5;  // where the other foot strikes within a cycle, in (0, 1)
  double guess_period_s = 1.1;      // a cycle's length until the stream has shown one, seconds
  double correction_seconds = 0.1;  // a small phase error is closed over this time
  double fade_cycles = 0.5;         // the cycle weight eases in and out over this many cycles
  double missed_step = 1.3;         // no strike for this many steps expected: out of the cycle
  CycleOptions cycles;              // gait range, max_change, step_share, min_stride
};

class LivePhase {
 public:
  explicit LivePhase(const LivePhaseOptions& options);

  // The next frame. strikes: per foot (left, right), the frame its contact began when this frame
  // found one (LiveFeet: LiveFoot::strike when struck_now; an earlier frame, found late), else
  // -1. ankles: each ankle's horizontal place (x, z) in the body's frame at this frame
  // (canonical_frame.h local), file units: how far a foot reaches between its strikes (the
  // extent of its path, as cycles.h measures a stride). O(1).
  void update(const std::array<long, 2>& strikes, const std::array<Eigen::Vector2d, 2>& ankles);

  double phase() const;                                  // [0, 1): the phase shown at this frame
  double predicted_phase() const;                        // [0, 1): the prediction it moves towards
  double cycle_weight() const { return weight_; }        // [0, 1], eased
  bool in_cycle() const { return in_cycle_; }
  double period_frames() const { return period_; }       // the expected cycle, frames
  long frame() const { return frame_; }                  // this frame's index (0 for the first)
  // Strikes so far that began a cycle the checks passed (a hand count for tests and metrics).
  int cycles() const { return cycles_; }

 private:
  void strike_cycle_foot(long at);
  void strike_other_foot(long at);
  void set_prediction(long at, double phase, double rate);
  double typical_period() const;

  LivePhaseOptions o_;
  long frame_ = -1;
  long last_cycle_strike_ = -1, last_other_strike_ = -1;
  long cycle_clock_ = 0;                        // the frame the cycle foot's next strike is awaited from
  double period_ = 0.0;                         // frames
  std::array<double, 5> recent_{};              // the last cycle lengths in the gait's range, frames
  int recent_count_ = 0;
  double other_share_ = 0.5;                    // the stream's own other-foot strike, share of its cycle
  bool has_other_share_ = false;
  long anchor_frame_ = 0;
  double anchor_phase_ = 0.0, rate_ = 0.0;      // prediction: anchor_phase + (t - anchor_frame) rate
  double shown_ = 0.0;                          // unwrapped
  bool in_cycle_ = false;
  double fade_ = 0.0, weight_ = 0.0;            // progress of the ease, and the eased weight
  std::array<Eigen::Vector2d, 2> reach_min_, reach_max_;
  std::array<bool, 2> reach_seen_{{false, false}};
  std::array<double, 2> stride_{{0.0, 0.0}};    // each foot's reach over its last stride, file units
  int cycles_ = 0;
};

}  // namespace mostyle
