#include "ui/panels/session_dialog.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include <imgui.h>
#include <imgui_internal.h>  // ImGui::BringWindowToDisplayFront

#include "ui/panels/layout.h"
#include "ui/panels/theme.h"

namespace mostyle::ui {
namespace {

constexpr std::chrono::seconds kMessageSeconds(4);

void copy_to(char* field, size_t size, const std::string& text) {
  const size_t n = std::min(text.size(), size - 1);
  text.copy(field, n);
  field[n] = '\0';
}

}  // namespace

void SessionDialog::open(Kind kind, const std::string& path) {
  copy_to(path_, sizeof path_, path);
  kind_ = kind;
  opening_ = true;
  close_ = false;
  error_.clear();
}

void SessionDialog::done() { close_ = true; }

void SessionDialog::failed(const std::string& sentence) { error_ = sentence; }

SessionDialog::Request SessionDialog::draw(const std::vector<std::string>& recent_sessions) {
  Request request;
  if (kind_ == Kind::kNone) return request;
  const bool save = kind_ == Kind::kSave;
  const char* title = save ? "Save session" : "Open session";
  bool focus = false;
  if (opening_) {
    ImGui::OpenPopup(title);
    opening_ = false;
    focus = true;
  }
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(0.5f * display.x, 0.3f * display.y), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
    kind_ = Kind::kNone;  // closed
    return request;
  }
  if (close_) {
    ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    kind_ = Kind::kNone;
    close_ = false;
    return request;
  }
  ImGui::TextUnformatted(save ? "Save the takes, every parameter, the camera and the playback to:"
                              : "Open the session (.mostyle) in:");
  if (focus) ImGui::SetKeyboardFocusHere();
  const float width = std::min(640.0f, 0.8f * display.x);
  ImGui::SetNextItemWidth(width);
  bool confirm = ImGui::InputText("##session_path", path_, sizeof path_,
                                  ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("A path, absolute or from the session's folder (else the first take's); Enter %s",
                      save ? "saves" : "opens");
  std::error_code ec;
  if (save && std::filesystem::exists(path_, ec))
    ImGui::TextColored(kWarningColor, "A file of that name is there: saving replaces it.");
  if (!save && !recent_sessions.empty()) {
    ImGui::TextDisabled("Recent sessions (a click fills the field, a double click opens):");
    for (const std::string& r : recent_sessions) {
      ImGui::PushID(r.c_str());
      if (ImGui::Selectable(std::filesystem::path(r).filename().string().c_str(), r == path_,
                            ImGuiSelectableFlags_AllowDoubleClick | ImGuiSelectableFlags_DontClosePopups)) {
        copy_to(path_, sizeof path_, r);
        confirm |= ImGui::IsMouseDoubleClicked(0);
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", r.c_str());
      ImGui::PopID();
    }
  }
  if (!error_.empty()) {  // said here, where the path can be corrected
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width);
    ImGui::TextColored(kErrorColor, "%s", error_.c_str());
    ImGui::PopTextWrapPos();
  }
  confirm |= ImGui::Button(save ? "Save" : "Open", ImVec2(96.0f, 0.0f));
  ImGui::SameLine();
  const bool cancel =
      ImGui::Button("Cancel", ImVec2(96.0f, 0.0f)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false);
  if (confirm) {
    request = Request{kind_, path_};
  } else if (cancel) {
    ImGui::CloseCurrentPopup();
    kind_ = Kind::kNone;
  }
  ImGui::EndPopup();
  return request;
}

void SessionMessage::set(const std::string& sentence, bool error) {
  text_ = sentence;
  error_ = error;
  if (error)
    until_.reset();  // stays until read and closed
  else
    until_ = std::chrono::steady_clock::now() + kMessageSeconds;
}

void SessionMessage::draw(bool hide_successes) {
  if (text_.empty()) return;
  if (until_ && std::chrono::steady_clock::now() > *until_) {
    text_.clear();
    return;
  }
  if (hide_successes && !error_) return;
  // Above the timeline, in the middle: read without covering the panels.
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(0.5f * display.x, display.y - playback_bar_height() - kLayoutMargin),
                          ImGuiCond_Always, ImVec2(0.5f, 1.0f));
  bool open = true;
  const ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing;
  if (ImGui::Begin("Session", &open, flags)) {
    // Over the panels it may lie on (the bottom strip's), though it takes no focus.
    ImGui::BringWindowToDisplayFront(ImGui::GetCurrentWindow());
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 0.5f * display.x);
    ImGui::TextColored(error_ ? kErrorColor : kOkColor, "%s", text_.c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::End();
  if (!open) text_.clear();
}

}  // namespace mostyle::ui
