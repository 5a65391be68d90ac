#pragma once
// The layers' weights per body part and per component (TakeLayer::component_weights), as the
// body-part controls read and set them for any number of takes: a part's row is one weight per
// take, set on every component of the decomposition whose region the part covers; a component's
// row is one weight per take too. A row is all set or all cleared (none: each layer's weight
// there), so that every component's weights sum as the layers' do. Plain data: no ImGui.
#include <optional>
#include <vector>

#include "engine/decompose/body_parts.h"
#include "engine/decompose/decompose_takes.h"
#include "engine/synthesize/mix_palette.h"
#include "ui/model/document.h"

namespace mostyle::ui {

// The parts the controls give weights to, legs first.
inline constexpr BodyPart kLayerParts[] = {BodyPart::kLegs, BodyPart::kArms, BodyPart::kSpine};

// Component c's weights, one per take of `takes`: each layer's own there, else its weight
// (weights: the constant weights the layers have, keyed_weights.h constant_weights). O(takes).
std::vector<double> component_row(const Document& d, int c, const std::vector<double>& weights);
// Whether component c has weights of its own (set, not following the layers' weights).
bool component_set(const Document& d, int c);
// Sets component c's weights (one per take), or clears them (none): the layers sized for the
// decomposition's components first (their regions recorded, DocumentControls::component_regions).
// O(k x takes).
void set_component_row(Document& d, const Decomposed& decomposition, int c, const std::optional<std::vector<double>>& row);

// The first component of `part` in the decomposition, or -1 when it has none: what a part's row
// shows.
int first_component_of(const Decomposed& decomposition, BodyPart part);
// Sets every component of `part` as set_component_row does.
void set_part_row(Document& d, const Decomposed& decomposition, BodyPart part, const std::optional<std::vector<double>>& row);
// The take every component of `part` comes from alone (weight 1 there, 0 elsewhere), or -1.
int part_from_take(const Document& d, const Decomposed& decomposition, BodyPart part);

// Weights after take i's weight was set to `value`: the others scaled so that all sum to 1 (or,
// when they sum to 0, sharing the rest equally), each kept within [lo, hi] (a mix's weights,
// document_fields.h kMixWeightRange). Pure.
std::vector<double> set_weight_keeping_sum(std::vector<double> weights, int i, double value, double lo = kMinMixWeight,
                                           double hi = kMaxMixWeight);

}  // namespace mostyle::ui
