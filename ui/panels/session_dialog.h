#pragma once
// The session files' two windows: the Save / Open dialog (a path field, the recent sessions, an
// error line where the path can be corrected) and the message shown above the timeline after a
// save or an open. They draw and return what the animator asked for; the editor does it
// (app/editor/editor.cpp) and tells them how it went. No files are touched here.
#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace mostyle::ui {

class SessionDialog {
 public:
  enum class Kind { kNone, kSave, kOpen };
  struct Request {
    Kind kind = Kind::kNone;  // kNone: nothing asked this frame
    std::string path;         // as typed
  };

  // Opens the dialog on the next draw(), its field holding `path`.
  void open(Kind kind, const std::string& path);
  bool is_open() const { return kind_ != Kind::kNone; }
  bool opening() const { return opening_ || close_; }  // a popup to open or close on the next draw()
  // Between ImGui::NewFrame() and ImGui::Render(): the dialog when open. A confirmed path (Enter,
  // the button, a double click on a recent session) is returned; the dialog stays open until
  // done() or failed() says how it went.
  Request draw(const std::vector<std::string>& recent_sessions);
  void done();                               // it worked: the dialog closes
  void failed(const std::string& sentence);  // it did not: said in the dialog, which stays

 private:
  Kind kind_ = Kind::kNone;
  bool opening_ = false;  // OpenPopup on the next draw()
  bool close_ = false;    // CloseCurrentPopup on the next draw()
  char path_[1024] = "";
  std::string error_;
};

// The last save's or open's sentence, above the timeline: a success fades after a few seconds,
// an error stays until closed.
class SessionMessage {
 public:
  void set(const std::string& sentence, bool error);
  void clear() { text_.clear(); }
  const std::string& text() const { return text_; }
  bool is_error() const { return error_; }
  // hide_successes: screenshots (a success would differ run to run).
  void draw(bool hide_successes);

 private:
  std::string text_;
  bool error_ = false;
  std::optional<std::chrono::steady_clock::time_point> until_;  // none: until closed
};

}  // namespace mostyle::ui
