#include "ui/model/edit_history.h"

#include <algorithm>
#include <optional>

#include "ui/model/session_file.h"

namespace mostyle::ui {
namespace {

// The takes of a snapshot, as a Document lists them.
std::vector<std::string> loaded_files(const WorkerSnapshot& snap) {
  if (snap.prepared) return snap.paths;
  return {};
}

}  // namespace

Document capture_document(const EditorState& state) {
  Document d = state.document;
  d.controls = document_controls(d.controls);
  return d;
}

void apply_document(const Document& document, EditorState& state, EngineLink& engine) {
  const Document before = capture_document(state);
  // A load on its way counts as loaded: undoing back to the loaded takes must replace it.
  const std::vector<std::string> takes = load_pending(engine) ? engine.requested_takes() : before.files;
  DocumentControls& c = state.document.controls;
  const int selected = c.selected_component, coordinate = c.dtw_coordinate;
  const std::vector<std::string> files = state.document.files;
  state.document = document;  // the engine link (EngineLink::sync) does what that makes stale
  state.document.files = files;  // loaded takes stay what they are until the new ones arrive
  c.selected_component = selected;
  c.dtw_coordinate = coordinate;
  if (!document.files.empty() && !same_files(takes, document.files))
    engine.load_files(document.files, WeightsOf::kNewTakes);  // a pair, or a palette of three or more
}

std::string apply_session_document(const Document& document, const std::string& session_path, EditorState& state,
                                   EngineLink& engine) {
  const std::vector<std::string> missing = missing_takes(document);
  std::vector<int> kept;
  for (size_t k = 0; k < document.files.size(); ++k)
    if (std::find(missing.begin(), missing.end(), document.files[k]) == missing.end()) kept.push_back(static_cast<int>(k));
  Document opened = missing.empty() || kept.empty() ? document : keep_takes(document, kept);
  if (kept.empty()) opened.files = capture_document(state).files;  // none there: the takes loaded stay
  if (kept.empty() && load_pending(engine)) opened.files = engine.requested_takes();
  apply_document(opened, state, engine);
  return missing_takes_message(session_path, missing, !kept.empty());
}

bool load_pending(const EngineLink& engine) {
  const WorkerStatus status = engine.status();
  if (status.stage == WorkerStage::kLoading || engine.load_waiting()) return true;
  if (engine.requested_a().empty()) return false;
  // A load the worker has finished (even its decomposition and mix: idle, nothing waiting) is
  // still on its way until poll() takes up its snapshot; a failed one, once polled, is not.
  if (!status.pending && !engine.has_news()) return false;
  return engine.requested_takes() != loaded_files(engine.snapshot());
}

void EditHistory::record(const EditorState& state, EngineLink& engine, bool item_active) {
  touched_ = touched_ || item_active || state.command_edits != seen_command_edits_;
  seen_command_edits_ = state.command_edits;
  if (item_active || load_pending(engine)) return;
  const Document now = capture_document(state);
  if (now.files.empty()) return;  // nothing loaded yet: no state to come back to
  const Document* top = history_.current();
  if (top == nullptr || touched_ || !same_files(now.files, top->files)) history_.commit(now);
  touched_ = false;
  if (!saved_) saved_ = *history_.current();
}

bool EditHistory::unsaved() const {
  const Document* top = history_.current();
  return top != nullptr && saved_ && !(*top == *saved_);
}

bool EditHistory::undo(EditorState& state, EngineLink& engine) {
  record(state, engine, false);
  const std::optional<Document> d = history_.undo();
  if (!d) return false;
  apply_document(*d, state, engine);
  touched_ = false;
  return true;
}

bool EditHistory::redo(EditorState& state, EngineLink& engine) {
  record(state, engine, false);
  const std::optional<Document> d = history_.redo();
  if (!d) return false;
  apply_document(*d, state, engine);
  touched_ = false;
  return true;
}

}  // namespace mostyle::ui
