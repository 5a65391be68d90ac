#pragma once
// The ImGui context for one run of the editor, set up the same way for the window and for
// offscreen runs: theme, font, and where (or whether) the layout is saved.
#include <string>

namespace mostyle::app {

class ImGuiContextScope {
 public:
  // persist_layout: save window positions in ~/.config/mostyle/imgui.ini ($XDG_CONFIG_HOME
  // when set). Screenshot and offscreen runs pass false: they neither read nor write it, so
  // their picture does not depend on the last session.
  explicit ImGuiContextScope(bool persist_layout);
  ~ImGuiContextScope();
  ImGuiContextScope(const ImGuiContextScope&) = delete;
  ImGuiContextScope& operator=(const ImGuiContextScope&) = delete;

 private:
  std::string ini_path_;  // ImGui keeps the pointer: it must outlive the context
};

}  // namespace mostyle::app
