#pragma once
// One take's alignment onto the reference: the feature aligned on, the DTW path, the
// smooth time warp, the matched ranges and how well each part matched. An immutable stage value
// between preparation and decomposition.
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "engine/align/alignment_feature.h"
#include "engine/align/cycle_registration.h"
#include "engine/align/dtw.h"
#include "engine/align/slope_dtw.h"
#include "engine/align/time_warp.h"
#include "engine/base/job_control.h"

namespace mostyle {

// What a take's time is matched on. By cycles (cycle_registration.h), when both takes repeat (cycles.h): each
// cycle of the reference is matched with a cycle of the take (a short take's reused in order,
// cycle_registration.h) and warped within it, so the whole reference is covered; outside its
// cycles the take gives its posture. Whole: one open-ended path between the two whole takes
// (also what cycles fall back to when either take does not repeat, and what --dtw paper does).
enum class TimeBase { kCycles, kWhole };
const char* time_base_name(TimeBase base);       // "cycles", "whole"
TimeBase parse_time_base(const std::string& name);  // throws InputError

enum class DtwMethod {
  kSlope,  // slope-limited, open-ended, smooth fractional warp (the default)
  kPaper,  // the paper's plain end-to-end DTW and B's frames averaged per A frame (--dtw paper)
};
const char* dtw_method_name(DtwMethod method);       // "slope", "paper"
DtwMethod parse_dtw_method(const std::string& name);  // throws InputError

struct AlignmentOptions {
  DtwMethod method = DtwMethod::kSlope;
  TimeBase time_base = TimeBase::kCycles;  // kPaper always aligns the whole takes
  AlignOn on = AlignOn::kAuto;  // kPaper always uses the left foot, as the paper does
  int band = -1;                // kPaper: Sakoe-Chiba half-width in frames, -1: none
  SlopeDtwOptions slope;        // kSlope
  double smoothing_frames = kWarpSmoothingFrames;
  void Validate() const;  // throws InputError
};
// Field by field, the slope options' too (the editor's undo compares the options it edits).
inline bool operator==(const AlignmentOptions& x, const AlignmentOptions& y) {
  return x.method == y.method && x.time_base == y.time_base && x.on == y.on && x.band == y.band && x.slope.max_slope == y.slope.max_slope &&
         x.slope.open_ends == y.slope.open_ends && x.slope.end_penalty == y.slope.end_penalty &&
         x.slope.pointer_budget_bytes == y.slope.pointer_budget_bytes && x.smoothing_frames == y.smoothing_frames;
}
inline bool operator!=(const AlignmentOptions& x, const AlignmentOptions& y) { return !(x == y); }

// A local cost this many times the path's median marks a poor match; a stretch of it lasting
// kPoorMatchSeconds is reported.
constexpr double kPoorMatchRatio = 3.0;
constexpr double kPoorMatchSeconds = 0.5;
// A take whose matched part is shorter than this fraction of it is reported.
constexpr double kMatchedFractionWarning = 0.6;

struct Alignment {
  AlignmentOptions options;
  AlignmentFeature feature;
  std::vector<std::pair<int, int>> path;  // the DTW path's vertices (i in A, j in B)
  double cost = 0.0;                      // along the path, feature units
  double end_penalty = 0.0;               // per frame left out (kSlope)
  TimeWarp warp;                          // U samples
  // Matched ranges, first and last frame, at the working rate.
  int a_first = 0, a_last = 0, b_first = 0, b_last = 0;
  // Per warp sample: |feature_a(a(u)) - feature_b(b(u))| over the median of it, and the warp's
  // slope db/da (B frames per A frame).
  Eigen::VectorXd cost_ratio, slope;
  double typical_cost = 0.0;  // that median, feature units
  // Sample ranges [first, last] where cost_ratio stays above kPoorMatchRatio for long enough.
  std::vector<std::pair<int, int>> poor;
  int frames_a = 0, frames_b = 0;     // the takes' lengths at the working rate
  std::vector<std::string> warnings;  // plain sentences: poor stretches, much left out ("A", "B")
  // Registration by cycles asked for but the takes aligned whole: why ("B has no cycles: no foot
  // strike of the right foot"); empty otherwise.
  std::string whole_because;
  // By cycles: B is the take registered onto A (cycle_registration.h), and this is the take's own
  // frame at each of B's frames (NaN where it gives its posture only); empty when aligned whole.
  Eigen::VectorXd b_source;
  bool by_cycles() const { return b_source.size() > 0; }
  // By structure (align_by_structure): rest matched to rest, action to action.
  bool by_structure = false;
  // Where B lacks a part of A's structure or has one A lacks, what was done ("B has no rest
  // before its action: it holds its first pose over A's rest, 0.0-0.8 s"); plain sentences.
  std::vector<std::string> notes;
};

// A take as an alignment's warnings name it: its name and its file's frame rate, so that frames
// are counted as the file counts them (0: at the working rate).
struct AlignedTake {
  std::string name;
  double file_fps = 0.0;
};
// The warnings of `al` (poor stretches, much left out) in plain sentences naming the takes, frames
// counted in their files and times in seconds; fps: the working rate. O(poor stretches).
std::vector<std::string> alignment_warnings(const Alignment& al, double fps, const AlignedTake& a, const AlignedTake& b);

// Aligns B onto A (both canonical, B retargeted to A's bones, fps their common rate). Throws
// InputError (bad options, missing joints, takes too short) or Cancelled.
// Cost: the DTW, O(Fa x Fb x features) time, bounded memory (slope_dtw.h, dtw.h).
Alignment align_takes(const CanonicalMotion& a, const CanonicalMotion& b, const FeatureJoints& joints,
                      double leg_length, double fps, const AlignmentOptions& options, JobControl* control = nullptr);

// Aligns the take registered onto A by cycles (register_by_cycles, one skeleton, fps their rate):
// 1:1 between cycles, and within each reference cycle the slope-limited DTW with closed ends
// (options.slope.max_slope; a straight line where the two cycles' lengths differ more than that
// allows), then smoothed as smooth_warp does over kCycleWarpSmoothing of the take's typical cycle
// (at least options.smoothing_frames): the warp keeps each cycle's length and the broad shape of
// its timing, not the sharp bends that would play one take up to max_slope times as fast for a
// moment. A few frames of smoothing are not enough at 120 fps, where a frame is short: the
// smoothing is a share of the cycle, not a count of frames. Covers all of A and all of the
// registered take. Throws InputError (bad options, missing joints) or Cancelled. Cost: the sum over cycles of
// their DTWs, O(sum of Lr x Lt x features), plus O(Fa + V).
// Test: "alignment pipeline: no pops on the shared motions' hardest pairs, across conventions"
// (tests/engine/worker/alignment_pipeline_test.cpp); the quality run's `fast` column (docs/quality.md).
constexpr double kCycleWarpSmoothing = 0.2;

// Aligns B onto A (as align_takes does) piece by piece along their structures (action_structure.h:
// a, b the spans of A and B): the rest before A's action onto B's, the moving span onto B's by the
// slope-limited DTW with closed ends (a straight line where their lengths differ more than
// options.slope.max_slope allows), the rest after onto B's. Where B lacks a rest A has, B holds its
// nearest pose (its first or last) over it; over a rest of B that A lacks, A holds its nearest
// pose (a hold of A: the path stays on A's frame while B advances, common_timeline.h); A at rest
// throughout is matched with B's rest before its action, then holds while B's action plays; B at
// rest throughout is laid on the whole of A. Covers all of A and all of B, never cutting either
// (frames only advance or hold). notes: say what was held.
// Throws InputError (bad options, missing joints, spans that do not fit the takes) or Cancelled.
// Cost: the moving spans' DTW, O(La x Lb x features), plus O(Fa + Fb).
Alignment align_by_structure(const CanonicalMotion& a, const ActionSpans& a_spans, const CanonicalMotion& b,
                             const ActionSpans& b_spans, const FeatureJoints& joints, double leg_length, double fps,
                             const AlignmentOptions& options, JobControl* control = nullptr);
Alignment align_by_cycles(const CanonicalMotion& a, const RegisteredMotion& b, const FeatureJoints& joints,
                          double leg_length, double fps, const AlignmentOptions& options, JobControl* control = nullptr);

}  // namespace mostyle
