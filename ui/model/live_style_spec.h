#pragma once
// What the live source styles with, taken from the editor as it shows the takes: a pair the
// first take as the neutral and the second as the style, at the pair's alpha; a palette's mix the
// stream standing in for the first take, the others the styles at their mix weights (as
// `mostyle-cli live --mix`); a palette's transfer the stream standing in for the content, its
// neutral take (or the content itself) the neutral, every other take a style at its strength.
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

// The plan for `takes` loaded takes (two or more) in the document's mode:
//   a pair (two takes): [0, 1], strength pair_alpha;
//   a mix (three or more, transfer off): [0, 1, ..., takes - 1], the stream standing in for take
//     0, strengths the weights of takes 1 .. takes - 1 (Document::weights; equal weights while
//     they are not one per take, as the mix takes them);
//   a transfer (three or more, transfer on): the content is take 0 (the editor prepares the
//     palette with its content first) and the stream stands in for it; the neutral is
//     transfer_neutral's (with content_neutral the content take itself, the nearest to the
//     performer's own neutral there is), the styles every other take in order, strengths their
//     PaletteControls::strengths (1 where one is not set).
// Each strength clamped to [-1, 2]. The one place the live source reads the document's weights:
// the editor asks for it every frame, and the takes only change with the mode, the neutral or the
// number of takes (a change of strengths changes only the strengths). Fewer than two takes: an
// empty plan. O(takes).
LiveStylePlan live_style_plan(const Document& document, int takes);

// live_style_plan's strengths.
std::vector<double> live_strengths(const Document& document, int takes);

// The loaded takes' clips in live_style_plan's order, with its strengths. Throws InputError when
// fewer than two takes are loaded. O(takes): the clips are shared, not copied.
LiveStyleSpec live_style_spec(const PreparedTakes& takes, const Document& document);

}  // namespace mostyle::ui
