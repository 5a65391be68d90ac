#pragma once
// Every field of a Document (ui/model/document.h), once: its name as a session file spells it and what
// a change to it makes stale. Equality (undo sees a change), what undo and redo must redo
// (stale_after) and the decomposition check are all made from this one list: a field added to
// Document, SessionControls, PaletteControls or BlendParameters goes here, and nowhere else.
#include "ui/model/document.h"

namespace mostyle::ui {

// What a change makes stale, from least to most: the picture only (drawn again next frame), the
// mix (mix_palette again, on the UI thread), the decomposition (the worker decomposes and mixes
// again), the alignment (the worker prepares the takes again), the takes (loaded again).
enum class Stale { kNothing = 0, kView, kMix, kDecomposition, kAlignment, kTakes };

// Calls f(name, x's field, y's field, stale) for each field of two documents, in one order.
template <typename F>
void document_fields(const Document& x, const Document& y, F&& f) {
  const BlendParameters &px = x.parameters, &py = y.parameters;
  f("parameters.alpha", px.alpha, py.alpha, Stale::kMix);
  f("parameters.components", px.components, py.components, Stale::kDecomposition);
  f("parameters.sparsity", px.sparsity, py.sparsity, Stale::kDecomposition);
  const SessionControls &cx = x.controls, &cy = y.controls;
  f("controls.mode", cx.mode, cy.mode, Stale::kDecomposition);
  f("controls.per_component", cx.per_component, cy.per_component, Stale::kMix);
  f("controls.component_alpha", cx.component_alpha, cy.component_alpha, Stale::kMix);
  f("controls.basic_motions", cx.basic_motions, cy.basic_motions, Stale::kDecomposition);
  f("controls.basic_sparsities", cx.basic_sparsities, cy.basic_sparsities, Stale::kDecomposition);
  f("controls.swap_level", cx.swap_level, cy.swap_level, Stale::kMix);
  f("controls.foot_lock", cx.foot_lock, cy.foot_lock, Stale::kMix);
  f("controls.align", cx.align, cy.align, Stale::kAlignment);
  f("controls.timing_a", cx.timing_a, cy.timing_a, Stale::kMix);
  f("controls.loop", cx.loop, cy.loop, Stale::kMix);
  f("controls.residual", cx.residual, cy.residual, Stale::kMix);
  f("controls.selected_component", cx.selected_component, cy.selected_component, Stale::kView);
  f("controls.dtw_coordinate", cx.dtw_coordinate, cy.dtw_coordinate, Stale::kView);
  const PaletteControls &wx = cx.palette, &wy = cy.palette;
  f("controls.palette.weights", wx.weights, wy.weights, Stale::kMix);
  f("controls.palette.per_part", wx.per_part, wy.per_part, Stale::kMix);
  f("controls.palette.part_weights", wx.part_weights, wy.part_weights, Stale::kMix);
  f("controls.palette.transfer", wx.transfer, wy.transfer, Stale::kMix);
  f("controls.palette.content", wx.content, wy.content, Stale::kMix);
  f("controls.palette.neutral", wx.neutral, wy.neutral, Stale::kMix);
  f("controls.palette.strengths", wx.strengths, wy.strengths, Stale::kMix);
  f("controls.palette.ghosts", wx.ghosts, wy.ghosts, Stale::kView);
  f("files", x.files, y.files, Stale::kTakes);
  f("view.overlay", x.overlay, y.overlay, Stale::kView);
}

// The most a change from `before` to `after` makes stale (kNothing: the same document).
Stale stale_after(const Document& before, const Document& after);

}  // namespace mostyle::ui
