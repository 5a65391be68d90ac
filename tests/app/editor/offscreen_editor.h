#pragma once
// An editor drawing into an OSMesa context, for tests that run its frames as the window does:
// by default on the bundled pair with k = 4, paused. The GL context and ImGui come first and go
// last, as in the programs.
#include <imgui.h>

#include "app/editor/editor.h"
#include "app/editor/imgui_context.h"
#include "tests/render/osmesa_context.h"

namespace mostyle::test {

inline app::EditorOptions paused_small_pair() {
  app::EditorOptions options;
  options.initial.parameters.components = 4;
  options.initial.paused = true;
  return options;
}

struct OffscreenEditor {
  glm::ivec2 size;
  OsMesaContext gl;
  app::ImGuiContextScope imgui{/*persist_layout=*/false};
  app::Editor editor;

  explicit OffscreenEditor(glm::ivec2 size_ = {960, 540}, const app::EditorOptions& options = paused_small_pair())
      : size(size_), gl(size_), editor(options) {}

  // One frame, 1/60 s after the last, with the display at `size`.
  void frame() {
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(static_cast<float>(size.x), static_cast<float>(size.y));
    io.DeltaTime = 1.0f / 60.0f;
    editor.frame(app::FrameInput{size, 1.0f / 60.0f});
  }
};

}  // namespace mostyle::test
