#pragma once
// What the live source styles with, taken from the editor as it shows the takes: the stream
// standing in for the first take, every other take a style added at its layer's weight (as
// `mostyle-cli live --mix`, a pair's B at its alpha); in a transfer the neutral take (or the
// content itself) the neutral, every other take a style at its strength.
#include <vector>

#include "engine/live/live_style.h"
#include "engine/align/prepare_takes.h"
#include "ui/model/document.h"

namespace mostyle::ui {

// Which of the loaded takes style the stream, and how much.
struct LiveStylePlan {
  std::vector<int> takes;         // loaded takes by index: [neutral, style_1, ..., style_n], n >= 1
  std::vector<double> strengths;  // one per style, each in the styler's range [-1, 2]
};

// The plan for `takes` loaded takes (two or more), one rule for any number: the stream stands in
// for take 0 (a transfer's content: the editor prepares the takes with it first); the neutral is
// take 0 itself, or in a transfer its neutral take (transfer_neutral); the styles are every other
// take in order, each at its weight as the layers give it (constant_weights: a pair's alpha, a
// mix's weights, a transfer's strengths), clamped to the styler's [-1, 2]. The one place the live
// source reads the document's weights: the editor asks for it every frame, and the takes only
// change with the mode, the neutral or the number of takes (a change of weights changes only the
// strengths). Fewer than two takes: an empty plan. O(takes).
LiveStylePlan live_style_plan(const Document& document, int takes);

// live_style_plan's strengths.
std::vector<double> live_strengths(const Document& document, int takes);

// The loaded takes' clips in live_style_plan's order, with its strengths. Throws InputError when
// fewer than two takes are loaded. O(takes): the clips are shared, not copied.
LiveStyleSpec live_style_spec(const PreparedTakes& takes, const Document& document);

}  // namespace mostyle::ui
