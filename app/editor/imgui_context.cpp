#include "app/editor/imgui_context.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include <imgui.h>

#include "ui/panels/theme.h"

namespace mostyle::app {
namespace {

std::string layout_file() {
  namespace fs = std::filesystem;
  fs::path dir;
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg) {
    dir = fs::path(xdg) / "mostyle";
  } else if (const char* home = std::getenv("HOME"); home && *home) {
    dir = fs::path(home) / ".config" / "mostyle";
  } else {
    return "";
  }
  std::error_code ec;
  fs::create_directories(dir, ec);
  return ec ? std::string() : (dir / "imgui.ini").string();
}

}  // namespace

ImGuiContextScope::ImGuiContextScope(bool persist_layout) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  if (persist_layout) ini_path_ = layout_file();
  io.IniFilename = ini_path_.empty() ? nullptr : ini_path_.c_str();
  ui::apply_theme();
  ui::load_fonts(16.0f);
}

ImGuiContextScope::~ImGuiContextScope() { ImGui::DestroyContext(); }

}  // namespace mostyle::app
