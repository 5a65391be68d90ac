#pragma once
// An ImGui context with no window and no renderer back-end, for panel tests: the display size
// is set by hand, the font atlas is built on the CPU, frames are NewFrame .. Render.
#include <imgui.h>

namespace mostyle::test {

class HeadlessImGui {
 public:
  explicit HeadlessImGui(float width = 1280.0f, float height = 720.0f) {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // tests never read or write a layout
    io.DisplaySize = ImVec2(width, height);
    io.DeltaTime = 1.0f / 60.0f;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  }
  ~HeadlessImGui() { ImGui::DestroyContext(); }
  HeadlessImGui(const HeadlessImGui&) = delete;
  HeadlessImGui& operator=(const HeadlessImGui&) = delete;

  void begin_frame() { ImGui::NewFrame(); }
  // Returns the frame's vertex count: something was drawn.
  int end_frame() {
    ImGui::Render();
    return ImGui::GetDrawData()->TotalVtxCount;
  }
};

}  // namespace mostyle::test
