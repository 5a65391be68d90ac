#pragma once
// The cycles of one take: where a repeated action repeats. Walks, runs and marches are
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
//
// A loop clip (a game's walk or run: one cycle whose last pose joins its first, loop_clip.h) is
// one closed cycle [0, L): gait when its feet step in turn, with where its foot strikes inside it.
// Gait cycles are only those of a locomotion: the other foot strikes well inside each (not both
// feet landing together, as in a jump), the hips stay near standing height (not getting up or
// crawling) and each foot moves a real distance against the body (not shifting weight on the
// spot). A take whose feet step in turn but fail these has no cycles; only a take whose feet do
// not step in turn is looked at for another repeated action.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "engine/align/action_structure.h"

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
  double min_amplitude = 0.04;   // leg lengths: joints that move less count as still
  int foot = -1;  // gait cycles begin at this foot's strikes (0 left, 1 right); -1: the foot giving more
  // The other foot strikes once in a gait cycle, within [step_share, 1 - step_share] of it (a step
  // of each); nearer its ends the feet land together.
  double step_share = 0.2;
  double min_hips_height = 0.7;  // leg lengths: the hips above the ankles' lowest, all through a gait cycle
  double min_stride = 0.2;       // leg lengths: each ankle's horizontal reach against the body within a gait cycle
  void Validate() const;         // throws InputError on a bad value
};

// The joints the gait checks read, as joint indices of the canonical poses (columns 3j to 3j + 2);
// -1 where not known, and the checks that need it (the hips' height, the feet's strides) are
// then skipped.
struct GaitJoints {
  int hips = -1;
  std::array<int, 2> ankles{{-1, -1}};  // left, right
};

// A loop is at most this many gait cycles (options.max_gait_s each) long; its pose comes back to
// its first at most this many times less one in between.
constexpr int kMaxLoopCycles = 2;
// A take's one gait cycle that is not a loop's is gait only when it covers this share of the
// take's moving span.
constexpr double kLoneGaitShare = 0.5;

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
  // The take read as rest, actions and rest (action_structure.h), on the poses the cycles were
  // read from; a periodic take's cycles are the strokes of its moving span.
  ActionSpans spans;
  bool loops() const { return loop_frames > 0; }
  int frames_in_cycles() const;
};

// Where a take shown at `frames` (its frame, fractional, at each shown frame: a mix's sources)
// starts one of its cycles: the shown frames k where frames[k] reaches a cycle's begin from below
// (frame 0 when it is one exactly). In order; a cycle shown twice is marked twice.
// O(K log cycles): it runs on the alpha slider's path.
std::vector<int> cycle_starts_at(const TakeCycles& cycles, const Eigen::VectorXd& frames);

// The loop a take is, as detect_cycles reads it (TakeCycles::loop_frames): loop_clip.h
// loop_clip_frames for a take of at most kMaxLoopCycles gait cycles; 0 for any other, and for a
// take at rest throughout or at rest at both ends (a one-shot action's first and last poses are
// alike because it stands still there, not because it repeats). Contacts
// detected across the loop's end (foot_contact.h detect_foot_contacts) use it. local: F x 3M
// canonical poses, leg_length what its speeds are judged in (the same units). O(F x M).
int cycle_loop_frames(const Eigen::MatrixXd& local, double fps, double leg_length, const CycleOptions& options = {});
// The same for a take whose spans are already read (find_action_spans of local).
int cycle_loop_frames(const Eigen::MatrixXd& local, double fps, const ActionSpans& spans, const CycleOptions& options = {});

// The cycles of one take. contacts: F x 2 (left, right foot; foot_contact.h; for a loop clip
// detected across its end), local: F x 3M joint positions in the canonical frame
// (canonical_frame.h: the travel and heading taken out), fps their rate, leg_length the size that
// amplitudes are judged by (same units as local), joints: where the hips and ankles are in local.
// A loop clip (cycle_loop_frames) is one cycle [0, L), its strikes read across its end (the cycle
// may end at F when frame 0 would follow the last); a loop that holds two gait cycles has the
// strike-cut ones inside it instead. Gait when either foot gives at least one cycle that passes
// the checks above (the foot with more cycles, then more frames in them, the left on a tie; only
// options.foot when it names one), with strike_phase where that foot strikes in a loop's cycle;
// else, when the feet do not step in turn, periodic when the joints that move repeat (a loop:
// its one cycle), else none; reason says what the gait cycles lacked. Throws InputError on
// mismatched sizes, joints outside local, fps or leg_length not above 0, or bad options. O(F x M)
// for gait; O(F x P) more for another action (P: the longest period tried, in frames).
TakeCycles detect_cycles(const Eigen::MatrixXd& contacts, const Eigen::MatrixXd& local, double fps, double leg_length,
                         const CycleOptions& options = {}, const GaitJoints& joints = {});

// The structure of a take in words: "gait: 6 cycles (left foot)", "periodic: 4 strokes of the
// left hand (1.2-5.6 s) between rests", "one action (0.8-3.1 s) between rests", "2 actions
// (0.5-1.9 s, 2.6-4.0 s), a rest before", "at rest throughout", "periodic: a loop of 1.00 s".
// fps: the rate the cycles' frames are at. O(cycles + actions).
std::string action_structure_summary(const TakeCycles& cycles, double fps);

}  // namespace mostyle
