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
#include "engine/trajectory/weight_keys.h"
#include "engine/decompose/decompose_params.h"

namespace mostyle::ui {

// The decomposition the animator asks for (defaults from the paper's figures).
struct BlendParameters {
  int components = 10;    // k
  double sparsity = 0.1;  // f in (0, 1]: fraction of non-zeros kept per component
};

// The style palette's controls beyond the weights (Document::weights): weights per body part, or
// a transfer (a style change from a neutral take, or from the content itself, to a styled one put
// on a content take).
struct PaletteControls {
  bool per_part = false;                       // weights per body part (legs, arms, spine)
  std::vector<std::vector<double>> part_weights;  // [legs, arms, spine] x takes; empty row: the overall weights
  // Transfer mode instead of a mix. A pair in transfer mode puts B's style on A, A its own
  // neutral (content_neutral is then set): alpha is the strength.
  bool transfer = false;
  int content = 0, neutral = 1;                // transfer: takes by index; every other take is a style
  // Transfer: no neutral take, the content is its own neutral (content + s (style - content)):
  // every take but the content is a style, and `neutral` is kept for when one is chosen again.
  bool content_neutral = false;
  // Transfer: one per take (used for the styles). Their own field, not Document::weights: the
  // mix's weights stay as they were while the transfer is toggled on and off.
  std::vector<double> strengths;
  bool ghosts = false;                         // show each take's warped ghost in the viewport
};

// What the result of `takes` takes is called in the editor's words and file names: "transfer" in
// transfer mode (a palette's, or a pair's: B's style put on A), else "blend" for a pair and "mix"
// for a palette.
inline const char* result_name(int takes, bool transfer) {
  return transfer ? "transfer" : takes <= 2 ? "blend" : "mix";
}

// What the parameter panels edit beyond the weights and the decomposition's k and sparsity.
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
  // mix weight per take (a pair's (1 - alpha, alpha)); they replace Document::weights (a
  // transfer's strengths) while they fit the takes (ui/model/keyed_weights.h). Empty: the constant weights.
  WeightKeys keys;
  int selected_component = -1;           // components view; -1: none
  int dtw_coordinate = 1;                // DTW view: 0 lateral, 1 height, 2 forward
  PaletteControls palette;               // with three or more takes
};

struct Document {
  BlendParameters parameters;        // k, sparsity
  DocumentControls controls;         // selected_component and dtw_coordinate at their defaults
  // The loaded takes as paths: a pair is A then B (A twice for A with itself); a palette is every
  // take, the reference first. Empty: nothing loaded. The engine link sets them as takes arrive;
  // a load is a command (BlendSession::load_files), not an edit of this field.
  std::vector<std::string> files;
  // The mix's weight of each take, in the order of `files`, summing to 1: a pair's are
  // (1 - alpha, alpha) (pair_alpha), a palette's its sliders'. Not one per take (nothing loaded
  // yet, or takes just changed): equal weights are mixed (constant_weights). The engine link sizes
  // them when the takes change (weights_for_takes, ui/model/document_mix.h).
  std::vector<double> weights;
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

// A pair's alpha, as its two weights show it: weights[1] (0: take A, 1: take B); 0.5, the
// default, while the weights are not a pair's.
double pair_alpha(const Document& d);
// A pair's weights at alpha: (1 - alpha, alpha).
inline std::vector<double> pair_weights(double alpha) { return {1.0 - alpha, alpha}; }
// Sets the document's weights to a pair's at alpha: (1 - alpha, alpha).
inline void set_pair_alpha(Document& d, double alpha) { d.weights = pair_weights(alpha); }

// `controls` with what a Document leaves out (selected_component, dtw_coordinate) at defaults.
DocumentControls document_controls(DocumentControls controls);

// Whether two lists of takes name the same files in the same order, whatever the spelling
// ("a/../b.bvh" and "b.bvh", relative to the working folder or absolute). No file is opened.
bool same_files(const std::vector<std::string>& x, const std::vector<std::string>& y);

// The document with its takes in another order: take k of the result is take order[k] of `d`.
// Every per-take value follows its take (the weights, the palette's per-part weights and
// strengths, the neutral take's index; the content is the reference, take 0), so a take keeps
// its weight when another becomes the content. The files and the keys are left as they are (the
// takes are loaded again in the new order; weight_keys_edit.h reorder_keys). order: a
// permutation of 0..n-1 for n takes; a per-take vector of another length (not yet sized for
// these takes) is left as it is.
Document reorder_takes(const Document& d, const std::vector<int>& order);

// The document with only some of its takes (a session whose other takes are not there): take k
// of the result is take kept[k] of `d`, with its file and every per-take value as
// reorder_takes gives them, the weights scaled to sum to 1 again (equal weights when the kept
// ones sum to 0). A neutral take left out makes the content its own neutral. kept: distinct
// indices of takes of `d`, in the order wanted. The keys are left as they are (their weights
// no longer fit: the constant weights are mixed).
Document keep_takes(const Document& d, const std::vector<int>& kept);

}  // namespace mostyle::ui
