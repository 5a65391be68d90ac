#pragma once
// What the animator edits in the editor, as one plain value: the blend parameters, the session's
// controls (mode, options, alignment, transfer), the loaded takes and their layers (each take's
// weight), and the view options
// one expects to undo. The editor keeps one (EditorState::document, ui/model/editor_state.h): the
// panels change it, the engine link (EngineLink::sync) brings the engine to it. Undo and redo
// (ui/model/history.h) keep copies of it; a session file (ui/model/session_file.h) holds one.
// Plain data: no ImGui, no GL, no engine work. Its fields, their ranges and what a change to
// each makes stale are listed once, in ui/model/document_fields.h.
//
// Left out of undo and session files, because they are where one looks rather than what one
// made: the picked component (DocumentControls::selected_component, which hovering changes) and
// the coordinate the DTW view plots (DocumentControls::dtw_coordinate): the live document has them,
// its copies keep them at their defaults (document_controls). Not in a Document at all: the
// playback and the camera (the session files keep them beside it).
#include <optional>
#include <string>
#include <vector>

#include "engine/align/alignment.h"
#include "engine/decompose/body_parts.h"
#include "engine/decompose/decompose_params.h"
#include "engine/trajectory/weight_keys.h"

namespace mostyle::ui {

// The decomposition the animator asks for (defaults from the paper's figures).
struct DecompositionControls {
  int components = 10;    // k
  double sparsity = 0.1;  // f in (0, 1]: fraction of non-zeros kept per component
};

// One take's layer (engine/synthesize/mix_layers.h, after ozz-animation's BlendingJob): what the
// take adds to the result, for any number of takes.
struct TakeLayer {
  // Its weight. In a mix, the take's share of the result (the layers' weights sum to 1; a pair's
  // are (1 - alpha, alpha)). In a transfer, a style's strength, added from the neutral, while the
  // content's and the neutral's follow from the styles' (keyed_weights.h transfer_mix_weights):
  // the content 1, the neutral minus the strengths' sum.
  double weight = 0.0;
  // Per component of the decomposition (k), its weight there, mixed while weights per body part
  // are on (DocumentControls::per_part); none: `weight` there. Empty: `weight` everywhere. The body
  // parts' and the components' controls set them; a new decomposition finds its components'
  // by body region (fit_component_weights).
  std::vector<std::optional<double>> component_weights;
};
bool operator==(const TakeLayer& x, const TakeLayer& y);
inline bool operator!=(const TakeLayer& x, const TakeLayer& y) { return !(x == y); }

// The words in which the count of takes changes a label, and nothing else: a pair's takes are A
// (the reference) and B, and its result a blend, as the command line's `blend` has them.
//
// What the result of `takes` takes is called in the editor's words and file names: "transfer" in
// transfer mode (B's style put on A for a pair), else "blend" for a pair and "mix" for more.
inline const char* result_name(int takes, bool transfer) {
  return transfer ? "transfer" : takes <= 2 ? "blend" : "mix";
}
// Take i's letter: "A" and "B" in a pair, "" for more takes.
inline const char* take_letter(int take, int takes) { return takes == 2 ? (take == 0 ? "A" : "B") : ""; }

// What the parameter panels edit beyond the layers' weights and the decomposition's k and sparsity.
struct DocumentControls {
  DecompositionMode mode = DecompositionMode::kShared;
  // The layers' weights per component (TakeLayer::component_weights) mixed (shared mode): each
  // body part or component its own style.
  bool per_part = false;
  // The body region of each component the layers' component weights are for (the decomposition
  // they were set on): a new decomposition's component takes the weights of the first of its
  // region. Empty: not known (they are kept by index).
  std::vector<BodyRegion> component_regions;
  int basic_motions = 0;                 // paper mode: m levels (0: one decomposition)
  std::vector<double> basic_sparsities;  // per level, resized to m
  int swap_level = 0;                    // paper mode with m > 0: the level taken from B
  bool foot_lock = true;
  AlignmentOptions align;                // what the takes are aligned on and how (a change re-aligns)
  bool timing_a = false;                 // keep the reference's (A's) timeline instead of mixing the timing
  bool loop = false;                     // cut a seamless loop of whole gait cycles
  bool residual = true;                  // mix the takes' residual detail too (MixParams::residual)
  // A transfer instead of a mix: the reference (take 0) is the content, every other take but the
  // neutral a style added at its layer's weight from the neutral take (`neutral`), or from the
  // content itself (content_neutral: the content is its own neutral; `neutral` is kept for when
  // one is chosen again). A pair's transfer puts B's style on A, A its own neutral.
  bool transfer = false;
  int neutral = 1;
  bool content_neutral = false;
  bool ghosts = true;                    // show each take beside the result, where the result is in it
  // Style over time: the layers' weights keyed at seconds of the result, each key one weight per
  // take (as TakeLayer::weight: a pair's (1 - alpha, alpha), a transfer's with its strengths);
  // they replace the layers' weights while they fit the takes (ui/model/keyed_weights.h). Empty:
  // the constant weights.
  WeightKeys keys;
  int selected_component = -1;           // components view; -1: none
  int dtw_coordinate = 1;                // the takes' view: 0 lateral, 1 height, 2 forward
};

struct Document {
  DecompositionControls parameters;        // k, sparsity
  DocumentControls controls;         // selected_component and dtw_coordinate at their defaults
  // The loaded takes as paths: a pair is A then B (A twice for A with itself); a palette is every
  // take, the reference first. Empty: nothing loaded. The engine link sets them as takes arrive;
  // a load is a command (EngineLink::load_files), not an edit of this field.
  std::vector<std::string> files;
  // One layer per take, in the order of `files`: each take's weight (and per component). Not one
  // per take (nothing loaded yet, or takes just changed): equal weights are mixed
  // (constant_weights). The engine link sizes them when the takes change (layers_for_takes,
  // ui/model/document_mix.h).
  std::vector<TakeLayer> layers;
  bool overlay = false;              // the takes drawn on one spot instead of side by side
};

// Field by field, from the one list of a Document's fields (ui/model/document_fields.h): a field added
// to one of these structs goes into that list, or undo does not see it change.
bool operator==(const DecompositionControls& x, const DecompositionControls& y);
bool operator==(const DocumentControls& x, const DocumentControls& y);
bool operator==(const Document& x, const Document& y);
inline bool operator!=(const DecompositionControls& x, const DecompositionControls& y) { return !(x == y); }
inline bool operator!=(const DocumentControls& x, const DocumentControls& y) { return !(x == y); }
inline bool operator!=(const Document& x, const Document& y) { return !(x == y); }

// The layers' weights, one per take (Document::layers' weight in order).
std::vector<double> layer_weights(const Document& d);
// Sets the layers' weights to `weights`, one per take: the layers are made or cut to as many,
// each keeping its weights per component.
void set_layer_weights(Document& d, const std::vector<double>& weights);
// A pair in the words of A and B: the alpha its layers' weights show, B's (0: take A, 1: take
// B), 0.5 before a second take has a layer; and the layers of a pair at alpha (1 - alpha, alpha).
double pair_alpha(const Document& d);
inline void set_pair_alpha(Document& d, double alpha) { set_layer_weights(d, {1.0 - alpha, alpha}); }

// `controls` with what a Document leaves out (selected_component, dtw_coordinate) at defaults.
DocumentControls document_controls(DocumentControls controls);

// Whether two lists of takes name the same files in the same order, whatever the spelling
// ("a/../b.bvh" and "b.bvh", relative to the working folder or absolute). No file is opened.
bool same_files(const std::vector<std::string>& x, const std::vector<std::string>& y);

// The document with its takes in another order: take k of the result is take order[k] of `d`.
// Every per-take value follows its take (its layer, the neutral take's index; the content is the
// reference, take 0), so a take keeps its weight when another becomes the content. The files and the keys are left as they are (the
// takes are loaded again in the new order; weight_keys_edit.h reorder_keys). order: a
// permutation of 0..n-1 for n takes; a per-take vector of another length (not yet sized for
// these takes) is left as it is.
Document reorder_takes(const Document& d, const std::vector<int>& order);

// The document with only some of its takes (a session whose other takes are not there): take k
// of the result is take kept[k] of `d`, with its file and every per-take value as
// reorder_takes gives them, the weights scaled to sum to 1 again (equal weights when the kept
// ones sum to 0; a transfer's weights are strengths, and stay). A neutral take left out makes the content its own neutral. kept: distinct
// indices of takes of `d`, in the order wanted. The keys are left as they are (their weights
// no longer fit: the constant weights are mixed).
Document keep_takes(const Document& d, const std::vector<int>& kept);

}  // namespace mostyle::ui
