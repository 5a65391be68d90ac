#pragma once
// Every field of a Document (ui/model/document.h), once: its key as a session file spells it, the
// range of values the editor's controls allow, whether a session file keeps it, and what a
// change to it makes stale. Equality (undo sees a change), what undo and redo must redo
// (stale_after), the session file (ui/model/session_file.cpp: its keys,
// the ranges it reads with, the keys it refuses) and the panels' sliders are all made from this
// one list: a field added to Document, DocumentControls or DecompositionControls goes here, and
// nowhere else.
#include "engine/synthesize/mix_palette.h"
#include "engine/align/prepare_takes.h"
#include "ui/model/document.h"
#include "ui/model/weight_keys_edit.h"

namespace mostyle::ui {

// What a change makes stale, from least to most: the picture only (drawn again next frame), the
// mix (mix_palette again, on the UI thread), the decomposition (the worker decomposes and mixes
// again), the alignment (the worker prepares the takes again), the takes (loaded again).
enum class Stale { kNothing = 0, kView, kMix, kDecomposition, kAlignment, kTakes };

// The values a control allows, ends included unless open_low; for a list, each of its numbers;
// for the takes, how many. A slider and a session file read with the same range, so every
// session the editor writes reopens and a file cannot hold what no control could set.
struct Range {
  double lo = 0.0, hi = 0.0;
  bool open_low = false;  // lo itself is not allowed
};
// A pair's alpha as version 1 and 2 session files kept it (and each component's): the weights
// (1 - alpha, alpha) within the mix's bounds, as `blend --alpha` takes it (0 is A, 1 is B).
inline constexpr Range kAlphaRange{1.0 - kMaxMixWeight, kMaxMixWeight};
inline constexpr Range kComponentsRange{1, 40};
inline constexpr Range kSparsityRange{0.01, 1.0};        // also each basic-motion level's
inline constexpr Range kBasicMotionsRange{0, 5};
// A weight's control in a mix (any number of takes: the one rule `mix` and `blend` have), and a
// style's strength in a transfer.
inline constexpr Range kMixWeightRange{kMinMixWeight, kMaxMixWeight};
inline constexpr Range kStrengthRange{kMinStrength, kMaxStrength};
inline constexpr Range kTakesRange{0, kMaxPaletteTakes};  // how many takes; a take's index is below hi
inline constexpr Range kTakeIndexRange{0, kMaxPaletteTakes - 1};
// Each layer's weight as a document holds it (TakeLayer, and each weight of a key,
// DocumentControls::keys): the widest range any mode mixes with, a transfer's (its neutral take,
// or the content when it is its own neutral, loses what every style gains: keyed_weights.h
// transfer_mix_weights), so that a mix started from a transfer's weights is held too. The controls
// set them within kMixWeightRange or kStrengthRange; the engine judges the weights for the mode
// they are mixed in (MixParams::Validate) and the editor shows its sentence.
inline constexpr Range kLayerWeightRange{transfer_min_weight(kMaxPaletteTakes), transfer_max_weight(kMaxPaletteTakes)};
inline constexpr Range kNoRange{};                        // not a number (a choice, a flag, options)

// The levels swap_level may take with `basic_motions` levels: 0 to basic_motions - 1 (0 alone
// without levels). The one range that depends on another field.
inline Range swap_level_range(int basic_motions) { return Range{0, basic_motions > 1 ? basic_motions - 1.0 : 0.0}; }

struct Field {
  const char* key;   // "controls.palette.strengths": the session file's object path, dot separated
  Stale stale;       // what a change to it makes stale
  Range range;       // numbers only
  bool saved = true; // false: where one looks, not what one made (not in session files)
};

// Calls f(field, x's value, y's value) for each field of two documents, in one order (the order
// of a session file's keys). Doc: Document or const Document (a reader passes one document twice
// and fills it).
template <typename Doc, typename F>
void document_fields(Doc& x, Doc& y, F&& f) {
  f(Field{"takes", Stale::kTakes, kTakesRange}, x.files, y.files);
  f(Field{"layers", Stale::kMix, kLayerWeightRange}, x.layers, y.layers);
  auto &px = x.parameters, &py = y.parameters;
  f(Field{"parameters.components", Stale::kDecomposition, kComponentsRange}, px.components, py.components);
  f(Field{"parameters.sparsity", Stale::kDecomposition, kSparsityRange}, px.sparsity, py.sparsity);
  auto &cx = x.controls, &cy = y.controls;
  f(Field{"controls.mode", Stale::kDecomposition, kNoRange}, cx.mode, cy.mode);
  f(Field{"controls.per_part", Stale::kMix, kNoRange}, cx.per_part, cy.per_part);
  f(Field{"controls.component_regions", Stale::kMix, kNoRange}, cx.component_regions, cy.component_regions);
  f(Field{"controls.basic_motions", Stale::kDecomposition, kBasicMotionsRange}, cx.basic_motions, cy.basic_motions);
  f(Field{"controls.basic_sparsities", Stale::kDecomposition, kSparsityRange}, cx.basic_sparsities,
    cy.basic_sparsities);
  // Its range follows x's basic_motions as it is now: a reader has read that field already.
  f(Field{"controls.swap_level", Stale::kMix, swap_level_range(cx.basic_motions)}, cx.swap_level, cy.swap_level);
  f(Field{"controls.foot_lock", Stale::kMix, kNoRange}, cx.foot_lock, cy.foot_lock);
  f(Field{"controls.timing_a", Stale::kMix, kNoRange}, cx.timing_a, cy.timing_a);
  f(Field{"controls.loop", Stale::kMix, kNoRange}, cx.loop, cy.loop);
  f(Field{"controls.residual", Stale::kMix, kNoRange}, cx.residual, cy.residual);
  f(Field{"controls.transfer", Stale::kMix, kNoRange}, cx.transfer, cy.transfer);
  f(Field{"controls.neutral", Stale::kMix, kTakeIndexRange}, cx.neutral, cy.neutral);
  f(Field{"controls.content_neutral", Stale::kMix, kNoRange}, cx.content_neutral, cy.content_neutral);
  f(Field{"controls.ghosts", Stale::kView, kNoRange}, cx.ghosts, cy.ghosts);
  f(Field{"controls.keys", Stale::kMix, kLayerWeightRange}, cx.keys, cy.keys);
  f(Field{"controls.align", Stale::kAlignment, kNoRange}, cx.align, cy.align);
  f(Field{"controls.selected_component", Stale::kView, kNoRange, false}, cx.selected_component, cy.selected_component);
  f(Field{"controls.dtw_coordinate", Stale::kView, kNoRange, false}, cx.dtw_coordinate, cy.dtw_coordinate);
  f(Field{"view.overlay", Stale::kView, kNoRange}, x.overlay, y.overlay);
}

// Whether two values of a field are the same: their ==; key by key for the keys (the engine's
// WeightKey has none). What equality, stale_after and differs_at compare with.
template <typename T>
bool same_value(const T& x, const T& y) {
  return x == y;
}
inline bool same_value(const WeightKeys& x, const WeightKeys& y) { return same_keys(x, y); }

// Whether v is in r. Numbers a float slider set are judged as that float (0.01f is
// 0.0099999998 as a double, and is the slider's own end).
bool in_range(double v, const Range& r);

// The most a change from `before` to `after` makes stale (kNothing: the same document).
Stale stale_after(const Document& before, const Document& after);

// Whether a field whose change makes exactly `what` stale differs between x and y (kDecomposition:
// k, sparsity, the mode, the basic motions or their sparsities; kAlignment: the alignment).
bool differs_at(const Document& x, const Document& y, Stale what);

}  // namespace mostyle::ui
