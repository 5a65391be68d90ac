#pragma once
// Undo and redo in the editor: the live Document (ui/model/document.h) captured from the EditorState
// and the EngineLink, applied back (undo, redo, an opened session), and recorded as steps of a
// History (ui/model/history.h) at the right moments. No ImGui here: the editor says whether an ImGui
// item is held, so tests drive it without a window.
//
// A step is what the animator did between two moments when nothing is held: a slider dragged
// from press to release is one step, a checkbox or a combo one each, a load one when its takes
// arrive. What the editor changes by itself (a decomposition that arrives with another k resizes
// the per-component alphas) makes no step of its own: it joins the next one.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "ui/model/engine_link.h"
#include "ui/model/document.h"
#include "ui/model/editor_state.h"
#include "ui/model/history.h"

namespace mostyle::ui {

// What the animator edits now. Its files are the takes loaded (the worker's snapshot as the
// session last polled it), not those asked for. O(size of the controls).
Document capture_document(const EditorState& state);

// Makes `document` the editor's: the parameters, the controls (the picked component and the DTW
// view's coordinate stay), the overlay; and a load when the takes differ from those loaded or
// being loaded (a pair, or a palette of three or more: EngineLink::load_files). The engine link
// (EngineLink::sync) does the rest that changes: a re-alignment, a decomposition, a mix.
// Returns at once: the takes arrive on a later poll().
void apply_document(const Document& document, EditorState& state, EngineLink& engine);

// A document read from a session file at `session_path`: apply_document, except that takes not
// there are left out (keep_takes: the others load, with their weights), and when none is there the
// takes loaded stay (everything else is applied). Returns the sentence naming the missing files
// (missing_takes_message, ui/model/session_file.h), or "".
std::string apply_session_document(const Document& document, const std::string& session_path, EditorState& state,
                                   EngineLink& engine);

// A load or re-alignment asked of the session's worker and not yet published by it.
bool load_pending(const EngineLink& engine);

class EditHistory {
 public:
  explicit EditHistory(std::size_t steps = History::kDefaultSteps) : history_(steps) {}

  // Once per frame, after the panels. item_active: an ImGui item is held this frame
  // (ImGui::IsAnyItemActive(): a slider being dragged, a field being typed in). Commits the live
  // Document when nothing is held, no load is pending and something is loaded, if an item was
  // held or a command edited it (EditorState::command_edits) since the last commit or the takes
  // changed (the first one sets the starting state).
  void record(const EditorState& state, EngineLink& engine, bool item_active);
  // Records what is there, steps back (forward) and applies that state. false: nothing to undo
  // (redo). Returns at once; a load it asks for arrives later.
  bool undo(EditorState& state, EngineLink& engine);
  bool redo(EditorState& state, EngineLink& engine);
  // The next record() commits even when no item was held (an opened session, a command).
  void mark_edited() { touched_ = true; }

  // Unsaved edits: the document as last recorded differs from the one saved or opened (or, before
  // any, from the first one recorded: the takes as they first arrived). Undoing back to it is no
  // edit. O(size of a Document).
  bool unsaved() const;
  // The document now (capture_document) is the one saved: after a session is written.
  void mark_saved(const Document& document) { saved_ = document; }
  // The next document recorded is the one saved: after a session is opened (its takes arrive later).
  void mark_opened() { saved_.reset(); }

  const History& history() const { return history_; }
  bool can_undo() const { return history_.can_undo(); }
  bool can_redo() const { return history_.can_redo(); }

 private:
  History history_;
  bool touched_ = false;  // an item was held, a command edited, or mark_edited(), since the last commit
  int seen_command_edits_ = 0;  // EditorState::command_edits at the last record()
  std::optional<Document> saved_;  // what unsaved() compares with; none: the next one recorded
};

}  // namespace mostyle::ui
