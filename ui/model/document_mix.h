#pragma once
// The one translation from what the animator set (a Document) to the engine's mix (MixParams),
// for any number of takes: the layers (engine/synthesize/mix_layers.h: each take's weight,
// constant_weights, and its weights per component; a transfer's content layer and its styles
// added at their strengths), the keys, the weight limits, the basic-motion level swapped, the
// timing and the clean-up options. Which document fields make
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

// The layers of takes `after` when the document's were those of takes `before`, by
// values_for_takes: the same takes keep theirs; takes added at the end keep theirs and each one
// added gets a layer at weight 0 (its weights per component 0 where the others have theirs), so
// the result is as it was; else equal weights and none per component (a pair's 0.5/0.5).
// O(after x k).
std::vector<TakeLayer> layers_for_takes(const std::vector<std::string>& before, const std::vector<TakeLayer>& layers,
                                        const std::vector<std::string>& after);

// A transfer's neutral for takes `after` (those of the layers before: `before`): new takes (not
// those before, nor those with takes added) take the neutral named so (named_neutral), else none
// (the content is its own neutral); the neutral stays among the takes.
void size_transfer_controls(DocumentControls& controls, const std::vector<std::string>& before,
                            const std::vector<std::string>& after);

// The layers' weights per component fitted to `decomposition`'s components (shared mode): kept
// when they were set on its components (DocumentControls::component_regions the same, or not
// known and as many), else each of its components takes the weights of the first component of
// its body region (none: the layer's weight); the regions become the decomposition's. Nothing
// when no layer has weights per component. O(k^2 x takes).
void fit_component_weights(Document& document, const Decomposed& decomposition);

}  // namespace mostyle::ui
