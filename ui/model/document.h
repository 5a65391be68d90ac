#pragma once
// What the animator edits in the editor, as one plain value: the blend parameters, the session's
// controls (mode, weights, options, alignment, palette), the loaded takes and the view options
// one expects to undo. Undo and redo (ui/model/history.h) keep a list of them; a session file
// (ui/model/session_file.h) holds one. Plain data: no ImGui, no GL, no engine work.
//
// Left out, because they are where one looks rather than what one made: the playback (position,
// speed, loop), the camera, the picked component (SessionControls::selected_component, which
// hovering changes) and the coordinate the DTW view plots (SessionControls::dtw_coordinate). A
// Document keeps those two at their defaults; the session files keep the camera and the playback
// beside the Document.
#include <string>
#include <vector>

#include "ui/model/blend_session.h"
#include "ui/model/editor_state.h"

namespace mostyle::ui {

struct Document {
  BlendParameters parameters;        // alpha, k, sparsity
  SessionControls controls;          // selected_component and dtw_coordinate at their defaults
  // The loaded takes as paths: a pair is A then B (A twice for A with itself); a palette is every
  // take, the reference first. Empty: nothing loaded.
  std::vector<std::string> files;
  bool overlay = false;              // ViewOptions::overlay: the takes on one spot, not side by side
};

// Field by field, from the one list of a Document's fields (ui/model/document_fields.h): a field added
// to one of these structs goes into that list, or undo does not see it change.
bool operator==(const BlendParameters& x, const BlendParameters& y);
bool operator==(const PaletteControls& x, const PaletteControls& y);
bool operator==(const SessionControls& x, const SessionControls& y);
bool operator==(const Document& x, const Document& y);
inline bool operator!=(const BlendParameters& x, const BlendParameters& y) { return !(x == y); }
inline bool operator!=(const PaletteControls& x, const PaletteControls& y) { return !(x == y); }
inline bool operator!=(const SessionControls& x, const SessionControls& y) { return !(x == y); }
inline bool operator!=(const Document& x, const Document& y) { return !(x == y); }

// `controls` with what a Document leaves out (selected_component, dtw_coordinate) at defaults.
SessionControls document_controls(SessionControls controls);

// Whether two lists of takes name the same files in the same order, whatever the spelling
// ("a/../b.bvh" and "b.bvh", relative to the working folder or absolute). No file is opened.
bool same_files(const std::vector<std::string>& x, const std::vector<std::string>& y);

// The palette's controls with its takes in another order: take k of the result is take order[k]
// of `c`. Every per-take value follows its take (weights, per-part weights, strengths, the
// neutral take's index; the content is the reference, take 0), so a take keeps its weight when
// another becomes the content. order: a permutation of 0..n-1 for n takes; a per-take vector of
// another length (not yet sized for these takes) is left as it is.
PaletteControls reorder_takes(const PaletteControls& c, const std::vector<int>& order);

// Whether going from `x` to `y` needs a new decomposition: a field whose change makes the
// decomposition stale differs (k, sparsity, the mode, the basic motions or their sparsities;
// ui/model/document_fields.h).
bool decomposition_differs(const Document& x, const Document& y);

}  // namespace mostyle::ui
