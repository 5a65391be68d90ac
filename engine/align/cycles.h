#pragma once
// The cycles of one take (issue 16): where a repeated action repeats. Walks, runs and marches are
// cut into gait cycles at foot strikes; other repeated actions (waving) into periods of the
// joints that move most; a take that does not repeat (raising both hands once, standing) has
// none. A style lives in one cycle's shape and timing, so cycles are what lets a few seconds of a
// style be registered onto a take of any length.
//
// A gait cycle runs from one strike of a foot to its next, with a strike of the other foot in
// between (a step of each). The cycles of a take keep their own lengths (its cycle-to-cycle
// variation); a span that is not a cycle (standing, a start or a stop, a turn on the spot, a
// stumble: a gap between strikes much longer or shorter than the take's typical cycle) is left
// out, so cycles need not follow one another.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace mostyle {

enum class CycleKind { kNone, kGait, kPeriodic };
const char* cycle_kind_name(CycleKind kind);  // "none", "gait", "periodic"

struct Cycle {
  int begin = 0, end = 0;  // frames [begin, end) of the take; frame `end` starts what follows
  int frames() const { return end - begin; }
};

struct CycleOptions {
  double min_gait_s = 0.5, max_gait_s = 2.6;  // a gait cycle (two steps), seconds
  double min_period_s = 0.3, max_period_s = 2.6;  // a period of another repeated action
  // A cycle more than this fraction longer or shorter than the median of the take's candidates
  // is not one (a pause, a turn on the spot, a stumble).
  double max_change = 0.45;
  double min_periodicity = 0.5;  // correlation of the moving joints with themselves one period on
  double min_amplitude = 0.04;   // leg lengths: joints that move less count as still
  int foot = -1;  // gait cycles begin at this foot's strikes (0 left, 1 right); -1: the foot giving more
  void Validate() const;         // throws InputError on a bad value
};

struct TakeCycles {
  CycleKind kind = CycleKind::kNone;
  std::vector<Cycle> cycles;  // in order, not overlapping; empty for kNone
  int foot = -1;              // gait: the foot whose strikes begin the cycles (0 left, 1 right)
  double period = 0;          // periodic: the period found, frames; gait: the median cycle, frames
  // A loop clip (its last pose joins its first, the root's travel apart): L, the frames of one
  // repeat (F - 1 when the last frame repeats the first, F when the first would follow the last);
  // 0 for a take that is not a loop. Frame f + L shows frame f's pose, the root moved on by the
  // loop's travel, so a loop's cycle may be read across its end.
  int loop_frames = 0;
  // Gait: where `foot` strikes within each cycle, as a fraction of it: 0 for cycles begun at its
  // strikes; a loop's one cycle [0, L) begins where the clip begins, its strike inside it.
  double strike_phase = 0.0;
  // Why the take has no cycles, or no gait cycles ("no foot strike of the right foot"); empty
  // for gait cycles.
  std::string reason;
  bool loops() const { return loop_frames > 0; }
  int frames_in_cycles() const;
};

// Frames where a foot lands: contacts(f, foot) planted and not at f - 1 (never frame 0: a take
// that starts planted has not struck). contacts: F x 2, 1 planted. O(F).
std::vector<int> foot_strikes(const Eigen::MatrixXd& contacts, int foot);

// Where a take shown at `frames` (its frame, fractional, at each shown frame: a mix's sources)
// starts one of its cycles: the shown frames k where frames[k] reaches a cycle's begin from below
// (frame 0 when it is one exactly). In order; a cycle shown twice is marked twice.
// O(K log cycles): it runs on the alpha slider's path.
std::vector<int> cycle_starts_at(const TakeCycles& cycles, const Eigen::VectorXd& frames);

// The cycles of one take. contacts: F x 2 (left, right foot; foot_contact.h), local: F x 3M joint
// positions in the canonical frame (canonical_frame.h: the travel and heading taken out), fps
// their rate, leg_length the size that amplitudes are judged by (same units as local). Gait when
// either foot gives at least one cycle (the foot with more cycles, the left on a tie; only
// options.foot when it names one), else
// periodic when the joints that move repeat, else none. Throws InputError on mismatched sizes,
// fps or leg_length not above 0, or bad options. O(F x M) for gait; O(F x P) more for another
// action (P: the longest period tried, in frames).
TakeCycles detect_cycles(const Eigen::MatrixXd& contacts, const Eigen::MatrixXd& local, double fps, double leg_length,
                         const CycleOptions& options = {});

}  // namespace mostyle
