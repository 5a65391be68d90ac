#pragma once
// What the live source styles with, taken from the editor: the takes loaded, the first the
// neutral and the others the styles (as a transfer with a neutral), and each style's strength
// from the document's weights.
#include <vector>

#include "engine/live/live_style.h"
#include "engine/align/prepare_takes.h"
#include "ui/model/document.h"

namespace mostyle::ui {

// The strengths of the styles of `takes` loaded takes (takes - 1 of them), from the document: a
// palette's transfer strengths of takes 1 to takes - 1 (1 where one is not set yet), a pair's
// alpha (pair_alpha: its second weight). Each clamped to the styler's range [-1, 2]. The one place the live source reads the
// document's weights. O(takes).
std::vector<double> live_strengths(const Document& document, int takes);

// The takes as loaded ([neutral, style, ...]) with live_strengths. Throws InputError when fewer
// than two takes are loaded. O(takes): the clips are shared, not copied.
LiveStyleSpec live_style_spec(const PreparedTakes& takes, const Document& document);

}  // namespace mostyle::ui
