#include "ui/model/history.h"

#include <algorithm>

namespace mostyle::ui {

History::History(std::size_t steps) : steps_(std::max<std::size_t>(steps, 1)) {}

void History::commit(const Document& document) {
  if (!states_.empty() && states_[at_] == document) return;
  if (!states_.empty()) states_.erase(states_.begin() + static_cast<std::ptrdiff_t>(at_) + 1, states_.end());
  states_.push_back(document);
  at_ = states_.size() - 1;
  while (states_.size() > steps_ + 1) {
    states_.pop_front();
    --at_;
  }
}

std::optional<Document> History::undo() {
  if (!can_undo()) return std::nullopt;
  --at_;
  return states_[at_];
}

std::optional<Document> History::redo() {
  if (!can_redo()) return std::nullopt;
  ++at_;
  return states_[at_];
}

void History::clear() {
  states_.clear();
  at_ = 0;
}

}  // namespace mostyle::ui
