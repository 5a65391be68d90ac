#pragma once
// Leaving the document with unsaved edits: closing the window, or opening another session over
// it, asks first (Save, Discard or Cancel) instead of losing them. The question as plain state,
// so that tests answer it without a window: the editor draws it as a modal and carries out a
// Save (which may first ask where, in the session dialog), then what was asked (the platform ends
// its loop once may_close(); the editor opens the session take_open() hands it).
#include <optional>
#include <string>

namespace mostyle::ui {

class UnsavedQuestion {
 public:
  enum class Answer { kSave, kDiscard, kCancel };
  enum class Leave { kClose, kOpen };  // what leaves the document: closing, or opening a session

  // The animator asks to leave the document: to close (kClose), or to open the session at
  // `path` over it (kOpen). unsaved: the document has edits not saved (EditHistory::unsaved).
  // Nothing unsaved: what was asked may be done at once. Else asking() until answered. A new
  // request replaces one not yet carried out.
  void request(bool unsaved, Leave leave = Leave::kClose, std::string path = std::string()) {
    leave_ = leave;
    path_ = std::move(path);
    saving_ = false;
    asking_ = unsaved;
    ready_ = !unsaved;
  }
  bool asking() const { return asking_; }
  Leave leave() const { return leave_; }
  const std::string& path() const { return path_; }  // kOpen: the session to open
  // kDiscard goes ahead; kCancel stays; kSave waits for saved() before going ahead.
  void answer(Answer a) {
    asking_ = false;
    saving_ = a == Answer::kSave;
    ready_ = a == Answer::kDiscard;
  }
  bool saving() const { return saving_; }
  // The save asked for by kSave: written (goes ahead) or not (failed or cancelled: stays).
  void saved(bool ok) {
    if (!saving_) return;
    saving_ = false;
    ready_ = ok;
  }
  // The platform may end now (and should, at the end of this frame).
  bool may_close() const { return ready_ && leave_ == Leave::kClose; }
  // The session to open now, once: an open asked for and answered (or nothing was unsaved).
  std::optional<std::string> take_open() {
    if (!ready_ || leave_ != Leave::kOpen) return std::nullopt;
    ready_ = false;
    return path_;
  }

 private:
  Leave leave_ = Leave::kClose;
  std::string path_;
  bool asking_ = false, saving_ = false, ready_ = false;
};

}  // namespace mostyle::ui
