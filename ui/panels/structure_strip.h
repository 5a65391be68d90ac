#pragma once
// A take's structure (ui/model/take_structure.h) drawn as a strip along one axis: its rests
// shaded grey, its actions lit in its colour, its strokes or gait cycles banded (every other one
// lighter, a tick where each begins), frames where it gives its posture only dark. The takes'
// rows draw it along each take's own frames, the alignment view beside the warp along both takes'.
#include <functional>

#include <imgui.h>

#include "engine/align/prepare_takes.h"

namespace mostyle::ui {

// The strip in [min, max] of the window's draw list over `frames` frames, frame 0 at min (left,
// or with `down` the top); own_frame_at(i): the take's own frame shown at the strip's frame i
// (ui/model/take_structure.h own_frame; NaN: its posture only). `color`: the take's. O(frames).
void draw_structure_strip(const PreparedTake& take, ImVec2 min, ImVec2 max, int frames, bool down, ImU32 color,
                          const std::function<double(int)>& own_frame_at);

}  // namespace mostyle::ui
