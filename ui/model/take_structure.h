#pragma once
// What a take does at each of its frames, as the editor's takes' views shade it: at rest, in an
// action, or in one of its strokes or gait cycles, from the engine's reading of the take
// (engine/align/action_structure.h: rest, actions, rest; engine/align/cycles.h: the strokes or
// gait cycles). Plain data: no ImGui; the panels draw it (ui/panels/structure_strip.h).
#include <functional>
#include <string>
#include <vector>

#include "engine/align/prepare_takes.h"

namespace mostyle::ui {

enum class FramePart {
  kPosture,  // no frame of its own: the take gives its posture only (registration.h)
  kRest,     // before, after or between its actions
  kAction,   // moving, outside its cycles
  kCycle,    // in a stroke or a gait cycle
};

struct FrameStructure {
  FramePart part = FramePart::kRest;
  int index = -1;  // the action's or the cycle's, from 0; -1 at rest
  bool operator==(const FrameStructure& o) const { return part == o.part && index == o.index; }
  bool operator!=(const FrameStructure& o) const { return !(*this == o); }
};

// The structure of `take` at its own frame `frame` (its file's frames at the working rate, as
// PreparedTake::world counts them; NaN: its posture only). O(cycles + actions).
FrameStructure frame_structure(const PreparedTake& take, double frame);

// Take's own frame at frame `frame` of its timeline as prepared (the alignment's frames): the same
// for a take aligned whole, the registered frame's source for one registered by cycles (NaN
// where it gives its posture only). O(1).
double own_frame(const PreparedTake& take, int frame);

// A run of a view's frames [begin, end) alike (one rest, one action, one showing of a cycle).
struct StructureSpan {
  int begin = 0, end = 0;
  FrameStructure structure;
};
// The runs of `frames` frames of a view, frame i showing the take's own frame own_frame_at(i)
// (own_frame for its timeline's frames): in order, covering [0, frames); a cycle shown again (the
// own frame going back, a registered take repeating it) begins a run of its own.
// O(frames x (cycles + actions)).
std::vector<StructureSpan> structure_spans(const PreparedTake& take, int frames,
                                           const std::function<double(int)>& own_frame_at);

// Plain words for a frame's structure, for tooltips: "gait cycle 2 of 5", "stroke 1 of 3",
// "action 1 of 2", "at rest before the action", "its posture only", ...
std::string frame_structure_words(const PreparedTake& take, double frame);

}  // namespace mostyle::ui
