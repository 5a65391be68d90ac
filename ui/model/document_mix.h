#pragma once
// The one translation from what the animator set (a Document) to the engine's mix (MixParams),
// for any number of takes: the weights (constant_weights: Document::weights, a transfer's made
// from its strengths), a pair's per-component or per-part weights, the keys, a transfer's weight limits,
// the basic-motion level swapped, the timing and the clean-up options. Which document fields make
// a mix stale is the field list's business (document_fields.h, Stale::kMix): whoever mixes
// compares documents with differs_at, not parameters by hand.
#include <string>
#include <vector>

#include "engine/synthesize/mix_palette.h"
#include "ui/model/document.h"

namespace mostyle::ui {

// The engine's mix parameters the document asks for, for `takes` takes decomposed as
// `decomposition`. Throws InputError when the weights or keys are refused (MixParams::Validate
// says why). O(k x takes).
MixParams mix_params_for(const Document& document, const Decomposed& decomposition, int takes);

// The weights of takes `after` (one per take, in order) when the document's `weights` were those
// of the takes `before`, the one rule for any number of takes: the same takes (same_files) keep
// theirs; takes added at the end (`before` the first of `after`) keep theirs and each one added
// gets 0 (a pair at 0.7/0.3 given a third take is 0.7/0.3/0); otherwise, or when `weights` is not
// one per take of `before`, equal weights (a pair's 0.5/0.5). O(after).
std::vector<double> weights_for_takes(const std::vector<std::string>& before, const std::vector<double>& weights,
                                      const std::vector<std::string>& after);

// The palette controls sized for `takes` takes: full strengths when theirs are not one per take,
// per-part rows cleared when they do not fit, the neutral among the takes.
void size_palette_controls(PaletteControls& controls, int takes);

}  // namespace mostyle::ui
