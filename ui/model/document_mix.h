#pragma once
// The one translation from what the animator set (a Document) to the engine's mix (MixParams),
// for any number of takes: the weights (constant_weights: Document::weights, a transfer's made
// from its strengths), a pair's per-component or per-part weights, the keys, a transfer's weight limits,
// the basic-motion level swapped, the timing and the clean-up options. Which document fields make
// a mix stale is the field list's business (document_fields.h, Stale::kMix): whoever mixes
// compares documents with differs_at, not parameters by hand.
#include <optional>
#include <string>
#include <vector>

#include "engine/synthesize/mix_palette.h"
#include "ui/model/document.h"

namespace mostyle::ui {

// The engine's mix parameters the document asks for, for `takes` takes decomposed as
// `decomposition`. Throws InputError when the weights or keys are refused (MixParams::Validate
// says why). O(k x takes).
MixParams mix_params_for(const Document& document, const Decomposed& decomposition, int takes);

// Per-take values (weights, strengths, a part's weights) of takes `before` for takes `after`, the
// one rule for any number of takes: the same takes (same_files) keep theirs; takes added at the
// end (`before` the first of `after`) keep theirs and each one added gets `added`. None otherwise,
// or when `values` is not one per take of `before`. O(after).
std::optional<std::vector<double>> values_for_takes(const std::vector<std::string>& before,
                                                    const std::vector<double>& values,
                                                    const std::vector<std::string>& after, double added);

// The weights of takes `after` when the document's `weights` were those of the takes `before`:
// values_for_takes with 0 for a take added (a pair at 0.7/0.3 given a third take is 0.7/0.3/0),
// else equal weights (a pair's 0.5/0.5). O(after).
std::vector<double> weights_for_takes(const std::vector<std::string>& before, const std::vector<double>& weights,
                                      const std::vector<std::string>& after);

// The take (not the content, take 0) whose file is named as the neutral one: "neutral" or
// "normal" as a word of its name (walk_normal.bvh, Neutral01.fbx); -1 when none is.
int named_neutral(const std::vector<std::string>& files);

// The palette controls of takes `before` (the document's weights then: weights_before) sized for
// takes `after`: the strengths and per-part weights by values_for_takes (a take added starts at 0:
// the result is as it was); a pair's transfer strength (its alpha) becomes B's. For other takes:
// full strengths, the neutral the take so named (named_neutral), else none (the content is its
// own neutral); per-part rows cleared; the neutral among the takes.
void size_palette_controls(PaletteControls& controls, const std::vector<std::string>& before,
                           const std::vector<double>& weights_before, const std::vector<std::string>& after);

}  // namespace mostyle::ui
