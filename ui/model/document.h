#pragma once
// What the animator edits in the editor, as one plain value: the blend parameters, the session's
// controls (mode, weights, options, alignment, palette), the loaded takes and the view options
// one expects to undo. The editor keeps one (EditorState::document, ui/model/editor_state.h): the
// panels change it, the engine link (BlendSession::sync) brings the engine to it. Undo and redo
// (ui/model/history.h) keep copies of it; a session file (ui/model/session_file.h) holds one.
// Plain data: no ImGui, no GL, no engine work. Its fields, their ranges and what a change to
// each makes stale are listed once, in ui/model/document_fields.h.
//
// Left out of undo and session files, because they are where one looks rather than what one
// made: the picked component (DocumentControls::selected_component, which hovering changes) and
// the coordinate the DTW view plots (DocumentControls::dtw_coordinate): the live document has them,
// its copies keep them at their defaults (document_controls). Not in a Document at all: the
// playback and the camera (the session files keep them beside it).
#include <string>
#include <vector>

#include "engine/align/alignment.h"
#include "engine/align/weight_keys.h"
#include "engine/decompose/decompose_params.h"

namespace mostyle::ui {

// The blend the animator asks for (defaults from the paper's figures).
struct BlendParameters {
  double alpha = 0.5;     // 0: take A, 1: take B
  int components = 10;    // k
  double sparsity = 0.1;  // f in (0, 1]: fraction of non-zeros kept per component
};

// The style palette: three or more takes mixed with weights, or a transfer (a style
// change from a neutral take, or from the content itself, to a styled one put on a content take).
struct PaletteControls {
  std::vector<double> weights;                 // one per take, summing to 1
  bool per_part = false;                       // weights per body part (legs, arms, spine)
  std::vector<std::vector<double>> part_weights;  // [legs, arms, spine] x takes; empty row: the overall weights
  bool transfer = false;                       // transfer mode instead of a mix
  int content = 0, neutral = 1;                // transfer: takes by index; every other take is a style
  // Transfer: no neutral take, the content is its own neutral (content + s (style - content)):
  // every take but the content is a style, and `neutral` is kept for when one is chosen again.
  bool content_neutral = false;
  std::vector<double> strengths;               // transfer: one per take (used for the styles)
  bool ghosts = false;                         // show each take's warped ghost in the viewport
};

// What the result of `takes` takes is called in the editor's words and file names: "blend" for a
// pair, "mix" for a palette, "transfer" for a palette in transfer mode.
inline const char* result_name(int takes, bool transfer) {
  return takes <= 2 ? "blend" : transfer ? "transfer" : "mix";
}

// What the parameter panels edit beyond the blend parameters (alpha, k, sparsity).
struct DocumentControls {
  BlendMode mode = BlendMode::kShared;
  bool per_component = false;            // shared mode: one alpha per component
  std::vector<double> component_alpha;   // resized to k when a decomposition arrives
  int basic_motions = 0;                 // paper mode: m levels (0: one decomposition)
  std::vector<double> basic_sparsities;  // per level, resized to m
  int swap_level = 0;                    // paper mode with m > 0: the level taken from B
  bool foot_lock = true;
  AlignmentOptions align;                // what the takes are aligned on and how (a change re-aligns)
  bool timing_a = false;                 // keep A's timeline instead of blending the timing
  bool loop = false;                     // cut a seamless loop of whole gait cycles
  bool residual = true;                  // blend the takes' residual detail too (BlendParams)
  // Style over time: the mix's weights keyed at seconds of the result, each key one
  // mix weight per take (a pair's (1 - alpha, alpha)); they replace alpha or the palette's weights
  // while they fit the takes (ui/model/keyed_weights.h). Empty: the constant weights.
  WeightKeys keys;
  int selected_component = -1;           // components view; -1: none
  int dtw_coordinate = 1;                // DTW view: 0 lateral, 1 height, 2 forward
  PaletteControls palette;               // with three or more takes
};

struct Document {
  BlendParameters parameters;        // alpha, k, sparsity
  DocumentControls controls;         // selected_component and dtw_coordinate at their defaults
  // The loaded takes as paths: a pair is A then B (A twice for A with itself); a palette is every
  // take, the reference first. Empty: nothing loaded. The engine link sets them as takes arrive;
  // a load is a command (BlendSession::load_files), not an edit of this field.
  std::vector<std::string> files;
  bool overlay = false;              // the takes drawn on one spot instead of side by side
};

// Field by field, from the one list of a Document's fields (ui/model/document_fields.h): a field added
// to one of these structs goes into that list, or undo does not see it change.
bool operator==(const BlendParameters& x, const BlendParameters& y);
bool operator==(const PaletteControls& x, const PaletteControls& y);
bool operator==(const DocumentControls& x, const DocumentControls& y);
bool operator==(const Document& x, const Document& y);
inline bool operator!=(const BlendParameters& x, const BlendParameters& y) { return !(x == y); }
inline bool operator!=(const PaletteControls& x, const PaletteControls& y) { return !(x == y); }
inline bool operator!=(const DocumentControls& x, const DocumentControls& y) { return !(x == y); }
inline bool operator!=(const Document& x, const Document& y) { return !(x == y); }

// `controls` with what a Document leaves out (selected_component, dtw_coordinate) at defaults.
DocumentControls document_controls(DocumentControls controls);

// Whether two lists of takes name the same files in the same order, whatever the spelling
// ("a/../b.bvh" and "b.bvh", relative to the working folder or absolute). No file is opened.
bool same_files(const std::vector<std::string>& x, const std::vector<std::string>& y);

// The palette's controls with its takes in another order: take k of the result is take order[k]
// of `c`. Every per-take value follows its take (weights, per-part weights, strengths, the
// neutral take's index; the content is the reference, take 0), so a take keeps its weight when
// another becomes the content. order: a permutation of 0..n-1 for n takes; a per-take vector of
// another length (not yet sized for these takes) is left as it is.
PaletteControls reorder_takes(const PaletteControls& c, const std::vector<int>& order);

}  // namespace mostyle::ui
