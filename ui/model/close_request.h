#pragma once
// Closing the editor with unsaved edits: the window's close asks first (Save, Discard or Cancel)
// instead of quitting. The question as plain state, so that tests answer it without a window: the
// editor draws it as a modal and carries out a Save (which may first ask where, in the session
// dialog); the platform ends its loop once may_close().
namespace mostyle::ui {

class CloseRequest {
 public:
  enum class Answer { kSave, kDiscard, kCancel };

  // The window asks to close. unsaved: the document has edits not saved (EditHistory::unsaved).
  // Nothing unsaved: may_close() at once. Else asking() until answered.
  void request(bool unsaved) {
    if (unsaved) asking_ = true;
    else closing_ = true;
  }
  bool asking() const { return asking_; }
  // kDiscard closes; kCancel stays open; kSave waits for saved() (saving_) before closing.
  void answer(Answer a) {
    asking_ = false;
    saving_ = a == Answer::kSave;
    closing_ = a == Answer::kDiscard;
  }
  bool saving() const { return saving_; }
  // The save asked for by kSave: written (closes) or not (failed or cancelled: stays open).
  void saved(bool ok) {
    if (!saving_) return;
    saving_ = false;
    closing_ = ok;
  }
  // The platform may end now (and should, at the end of this frame).
  bool may_close() const { return closing_; }

 private:
  bool asking_ = false, saving_ = false, closing_ = false;
};

}  // namespace mostyle::ui
