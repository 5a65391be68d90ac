#include "ui/panels/theme.h"

#include <cstdio>

#include <imgui.h>

namespace mostyle::ui {

void apply_theme() {
  ImGui::StyleColorsDark();
  ImGuiStyle& s = ImGui::GetStyle();
  s.WindowRounding = 6.0f;
  s.ChildRounding = 4.0f;
  s.FrameRounding = 4.0f;
  s.GrabRounding = 4.0f;
  s.PopupRounding = 4.0f;
  s.ScrollbarRounding = 6.0f;
  s.WindowBorderSize = 1.0f;
  s.FrameBorderSize = 0.0f;
  s.WindowPadding = ImVec2(10.0f, 10.0f);
  s.FramePadding = ImVec2(8.0f, 4.0f);
  s.ItemSpacing = ImVec2(8.0f, 6.0f);
  s.GrabMinSize = 10.0f;

  // Neutral greys with one accent (a calm blue), so the skeletons' colours stand out.
  ImVec4* c = s.Colors;
  const ImVec4 accent(0.33f, 0.55f, 0.85f, 1.0f);
  c[ImGuiCol_Text] = ImVec4(0.88f, 0.89f, 0.91f, 1.0f);
  c[ImGuiCol_TextDisabled] = ImVec4(0.50f, 0.52f, 0.55f, 1.0f);
  c[ImGuiCol_WindowBg] = ImVec4(0.125f, 0.130f, 0.140f, 0.94f);
  c[ImGuiCol_PopupBg] = ImVec4(0.125f, 0.130f, 0.140f, 0.98f);
  c[ImGuiCol_Border] = ImVec4(0.24f, 0.25f, 0.27f, 0.80f);
  c[ImGuiCol_FrameBg] = ImVec4(0.19f, 0.20f, 0.215f, 1.0f);
  c[ImGuiCol_FrameBgHovered] = ImVec4(0.24f, 0.25f, 0.27f, 1.0f);
  c[ImGuiCol_FrameBgActive] = ImVec4(0.28f, 0.29f, 0.31f, 1.0f);
  c[ImGuiCol_TitleBg] = ImVec4(0.10f, 0.105f, 0.115f, 1.0f);
  c[ImGuiCol_TitleBgActive] = ImVec4(0.14f, 0.15f, 0.165f, 1.0f);
  c[ImGuiCol_TitleBgCollapsed] = ImVec4(0.10f, 0.105f, 0.115f, 0.9f);
  c[ImGuiCol_CheckMark] = accent;
  c[ImGuiCol_SliderGrab] = ImVec4(0.45f, 0.62f, 0.88f, 1.0f);
  c[ImGuiCol_SliderGrabActive] = ImVec4(0.55f, 0.72f, 0.95f, 1.0f);
  c[ImGuiCol_Button] = ImVec4(0.22f, 0.23f, 0.25f, 1.0f);
  c[ImGuiCol_ButtonHovered] = ImVec4(0.28f, 0.36f, 0.48f, 1.0f);
  c[ImGuiCol_ButtonActive] = ImVec4(0.30f, 0.45f, 0.66f, 1.0f);
  c[ImGuiCol_Header] = ImVec4(0.20f, 0.21f, 0.23f, 1.0f);
  c[ImGuiCol_HeaderHovered] = ImVec4(0.26f, 0.30f, 0.37f, 1.0f);
  c[ImGuiCol_HeaderActive] = ImVec4(0.30f, 0.40f, 0.55f, 1.0f);
  c[ImGuiCol_Separator] = ImVec4(0.24f, 0.25f, 0.27f, 1.0f);
  c[ImGuiCol_ResizeGrip] = ImVec4(0.30f, 0.31f, 0.33f, 0.4f);
  c[ImGuiCol_ResizeGripHovered] = ImVec4(0.33f, 0.55f, 0.85f, 0.6f);
  c[ImGuiCol_ResizeGripActive] = accent;
  c[ImGuiCol_Tab] = ImVec4(0.16f, 0.17f, 0.18f, 1.0f);
  c[ImGuiCol_TabHovered] = ImVec4(0.28f, 0.36f, 0.48f, 1.0f);
  c[ImGuiCol_TabActive] = ImVec4(0.22f, 0.28f, 0.37f, 1.0f);
  c[ImGuiCol_PlotLines] = accent;
  c[ImGuiCol_PlotHistogram] = accent;
}

const char* load_fonts(float pixel_size) {
  static const char* const kCandidates[] = {
      "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
      "/usr/share/fonts/truetype/noto/NotoSans-Regular.ttf",
      "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
  };
  ImGuiIO& io = ImGui::GetIO();
  for (const char* path : kCandidates) {
    if (std::FILE* f = std::fopen(path, "rb")) {
      std::fclose(f);
      if (io.Fonts->AddFontFromFileTTF(path, pixel_size) != nullptr) return path;
    }
  }
  io.Fonts->AddFontDefault();
  return "";
}

}  // namespace mostyle::ui
