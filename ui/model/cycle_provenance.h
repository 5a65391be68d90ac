#pragma once
// Where each cycle of the result shown came from (registration by cycles): for each
// output cycle, which cycle of each take it shows, in that take's own file. The timeline's
// tooltip reads it (ui/panels/playback_panel.cpp); it is made once per result (a new blend or mix),
// not per frame, by the pair's and the palette's paths alike (ui/model/engine_link.cpp,
// ui/model/result_view.cpp). Plain data, no ImGui.
//
// The output is cut into spans where the reference shows one of its cycles (an output cycle) and
// the stretches in between (before the first, after the last, a gap the reference's cycle
// detection left out: outside cycles). Within a span, each take is said to show the cycle it
// shows at most of the span's frames (engine/align/prepare_takes.h cycles_shown), or, outside its
// cycles, the frames of its file shown there, or its posture only (a take registered by cycles
// gives only its posture where the reference does not repeat: frames_in_take is NaN there).
#include <string>
#include <vector>

#include <Eigen/Core>

namespace mostyle {
struct PreparedTakes;
}

namespace mostyle::ui {

enum class CycleSourceKind {
  kCycle,          // one of the take's own cycles
  kOutsideCycles,  // frames of its file that are in none of its cycles
  kPostureOnly,    // its posture on the reference's motion (no frame of its own)
};

// One take within one span of the result.
struct TakeCycleSource {
  std::string take;  // its name as the tooltip says it ("A", a file's name)
  CycleSourceKind kind = CycleSourceKind::kPostureOnly;
  int cycle = -1;    // kCycle: index of its cycle, 0-based (the one registration used, else as detected)
  // kCycle: that whole cycle; kOutsideCycles: the frames shown over the span. Frames of its file
  // at the file's own rate, inclusive; seconds from the file's first frame.
  int first_frame = 0, last_frame = 0;
  double begin_s = 0.0, end_s = 0.0;
  bool reused = false;  // kCycle: an earlier span of the result showed this cycle already
};

// One span of the result: an output cycle, or a stretch outside the reference's cycles.
struct CycleProvenance {
  int begin = 0, end = 0;  // output frames [begin, end), at the working rate
  int cycle = -1;          // the result's cycle, 0-based in output order; -1: outside the reference's cycles
  // The reference's cycle slot it plays (its timeline's cycle: PreparedTakes::slots), -1 outside;
  // the slot each registered take's pairs index.
  int slot = -1;
  std::vector<TakeCycleSource> takes;  // one per take, the reference first
};

// The spans of a result, in order, covering its K frames. prepared: the takes mixed (N);
// sources: K x N, each take's frame on its own timeline at each output frame (MixResult::sources);
// names: one per take (missing ones are called "take i"). Empty when K is 0. Asserts that sources
// has N columns. O(K x N log cycles).
std::vector<CycleProvenance> cycle_provenance(const PreparedTakes& prepared, const Eigen::MatrixXd& sources,
                                              const std::vector<std::string>& names);

// The span holding output frame `frame`, or -1 (no spans, a frame outside them). O(log spans).
int provenance_at(const std::vector<CycleProvenance>& spans, int frame);

// The tooltip for one span, several lines: its title with its time (fps: the output's rate, for
// seconds), then one line per take, e.g.
//   Cycle 3 of the result (2.10-3.20 s)
//   A: cycle 3, frames 250-379 of its file (2.08-3.16 s)
//   B: cycle 1, frames 12-140 of its file (0.10-1.17 s), reused
std::string provenance_text(const CycleProvenance& span, double fps);

}  // namespace mostyle::ui
