#include "ui/takes_panel.h"

#include <cfloat>

#include <imgui.h>

namespace mostyle::ui {
namespace {
const ImVec4 kErrorColor(1.0f, 0.45f, 0.40f, 1.0f);
const ImVec4 kWarningColor(0.95f, 0.78f, 0.35f, 1.0f);
const ImVec4 kDimColor(0.60f, 0.62f, 0.66f, 1.0f);
}  // namespace

void TakesPanel::draw(EditorState& state) {
  ImGui::SetNextWindowPos(ImVec2(12.0f, 12.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSizeConstraints(ImVec2(260.0f, 0.0f), ImVec2(520.0f, FLT_MAX));
  if (!ImGui::Begin("Takes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::End();
    return;
  }
  for (Take& take : state.takes) {
    ImGui::PushID(&take);
    if (take.ok()) {
      ImGui::ColorEdit3("##color", &take.color.x, ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_NoLabel);
      ImGui::SameLine();
      ImGui::Checkbox(take.label.c_str(), &take.visible);
      if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("%s\n%d frames at %.0f fps, %zu joints", take.path.c_str(), take.frames(),
                          take.rate(), take.parents.size());
      }
      for (const std::string& w : take.warnings) {
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextColored(kWarningColor, "%s", w.c_str());
        ImGui::PopTextWrapPos();
      }
    } else {
      ImGui::PushTextWrapPos(0.0f);
      ImGui::TextColored(kErrorColor, "%s", take.error.c_str());
      ImGui::PopTextWrapPos();
    }
    ImGui::PopID();
  }
  if (state.takes.empty()) ImGui::TextColored(kDimColor, "No takes.");

  if (ImGui::CollapsingHeader("View")) {
    ImGui::Checkbox("follow", &state.view.follow);
    ImGui::SameLine();
    ImGui::Checkbox("labels", &state.view.labels);
    ImGui::SameLine();
    ImGui::Checkbox("grid", &state.view.grid);
    ImGui::Checkbox("shadows", &state.view.shadows);
    ImGui::SameLine();
    ImGui::Checkbox("contacts", &state.view.contacts);
    if (ImGui::Button("Frame all")) state.view.request_reframe = true;
  }
  ImGui::End();
}

}  // namespace mostyle::ui
