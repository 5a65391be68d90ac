#pragma once
// One take's alignment onto the reference, as the takes' panel (layers_panel.h) shows it for the
// take picked, for any number of takes: the aligned joint's signals before and after warping with
// matched frames joined (paper Fig. 2), the local-cost matrix with the optimal path, and the
// match quality. Hover: the matched frames; click: jump there.
#include <string>

#include "ui/model/engine_link.h"
#include "ui/model/dtw_image.h"

namespace mostyle::ui {

// Take `take`'s name as the takes' views show it: its label (the animation's name, or the file's
// without its extension) without the start every take's label shares up to a '_' or '-'
// ("cmu142_walk_happy", "cmu142_walk_marching": "happy", "marching"), so that names fit narrow
// columns. O(takes).
std::string short_take_name(const PreparedTakes& p, int take);

// The frames of the reference and of take `take` that its alignment matched, first and last,
// counted as each take's file counts them: the take's own frames when it was registered by
// cycles (not the registered take's, which repeats its cycles), each at its file's rate (not the
// working rate). All 0 for a take not aligned (the reference, or none there). O(its matched
// frames).
struct MatchedFrames {
  int reference_first = 0, reference_last = 0, take_first = 0, take_last = 0;
};
MatchedFrames matched_frames_in_files(const PreparedTakes& p, int take);

// Whether take `take` is aligned far enough to plot: two frames of each signal and a path.
bool alignment_plottable(const PreparedTakes& p, int take);

// The alignment of take `take` (1 .. N - 1) onto the reference in the space left in the window
// being drawn: its header (the coordinate shown, what it was aligned on, the frames matched, its
// warnings), then the plots. `image` is take's cost picture (dtw_cost_image); `result` the result
// shown, for the playhead and the jumps (null: none).
void draw_alignment(EditorState& state, const PreparedTakes& p, int take, const MixResult* result,
                    const DtwCostImage& image);

}  // namespace mostyle::ui
