#pragma once
// Undo and redo over Documents (ui/model/document.h): a list of the states the animator made, and where
// in it the editor is. Pure: the editor decides when a state is a step (ui/model/edit_history.h: after
// the panels, not during a drag, not while a load is pending) and applies what undo and redo give.
#include <cstddef>
#include <deque>
#include <optional>

#include "ui/model/document.h"

namespace mostyle::ui {

class History {
 public:
  static constexpr std::size_t kDefaultSteps = 200;

  // Keeps at most `steps` undo steps (steps + 1 states); the oldest go first. steps >= 1.
  explicit History(std::size_t steps = kDefaultSteps);

  // Records `document` as the current state: a new step when it differs from the current one
  // (and the steps that could be redone are dropped), nothing when it is the same. The first
  // commit only sets the starting state. O(size of a Document), plus the dropped steps.
  void commit(const Document& document);
  // Steps back: the state to apply, or nothing at the oldest. The state undone stays for redo().
  std::optional<Document> undo();
  // Steps forward again after undo(): the state to apply, or nothing when there is none.
  std::optional<Document> redo();

  bool can_undo() const { return at_ > 0; }
  bool can_redo() const { return at_ + 1 < states_.size(); }
  // The state undo and redo move from; null before the first commit.
  const Document* current() const { return states_.empty() ? nullptr : &states_[at_]; }
  std::size_t undo_steps() const { return at_; }                    // how many undo() can go back
  std::size_t redo_steps() const { return states_.size() - at_ - (states_.empty() ? 0 : 1); }
  void clear();

 private:
  std::size_t steps_;
  std::deque<Document> states_;
  std::size_t at_ = 0;  // index of the current state in states_
};

}  // namespace mostyle::ui
