#include "ui/panels/takes_panel.h"
#include "ui/panels/theme.h"

#include <filesystem>
#include <string>

#include <imgui.h>

#include "ui/panels/layout.h"

namespace mostyle::ui {
namespace {

void messages(const char* id, const std::vector<std::string>& lines, const char* what, const ImVec4& color,
              const char* tooltip) {
  if (lines.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, color);
  const bool open = ImGui::TreeNode(id, "%zu %s%s", lines.size(), what, lines.size() == 1 ? "" : "s");
  ImGui::PopStyleColor();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tooltip);
  if (!open) return;
  ImGui::PushTextWrapPos(0.0f);
  for (const std::string& w : lines) ImGui::TextColored(color, "%s", w.c_str());
  ImGui::PopTextWrapPos();
  ImGui::TreePop();
}
}  // namespace

void TakesPanel::draw(EditorState& state) {
  // A fixed place and size from the layout: many warnings scroll inside, never push other panels.
  place_panel(PanelId::kTakes, state);
  if (!ImGui::Begin(panel_title(PanelId::kTakes))) {
    ImGui::End();
    return;
  }
  for (ShownMotion& take : state.shown) {
    ImGui::PushID(&take);
    if (take.ok()) {
      ImGui::ColorEdit3("##color", &take.color.x, ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_NoLabel);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Colour of this take's skeleton and label; click to change it");
      ImGui::SameLine();
      ImGui::Checkbox(take.label.c_str(), &take.visible);
      if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("Show or hide this take\nFolder: %s\n%d frames at %.0f fps, %zu joints",
                          std::filesystem::path(take.path).parent_path().string().c_str(), take.frames(), take.rate(),
                          take.parents.size());
      }
      // Collapsed to one line each; opened, the sentences wrap inside this panel. What the reader
      // did to the file and how the take was aligned are told apart.
      messages("##load", take.warnings, "load warning", kWarningColor,
               "What the file reader repaired or left out; click to read");
      messages("##alignment", take.notes, "alignment note", kWarningColor,
               "How this take was aligned onto the reference, where that changes what plays; click to read");
    } else {
      ImGui::PushTextWrapPos(0.0f);
      ImGui::TextColored(kErrorColor, "%s", take.error.c_str());
      ImGui::PopTextWrapPos();
    }
    ImGui::PopID();
  }
  if (state.shown.empty()) ImGui::TextColored(kDimColor, "No takes.");

  // The camera and where the takes stand, on one row.
  if (ImGui::Button("Frame all")) command_frame_all(state);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Turn and move the camera so that every skeleton is in view (F)");
  ImGui::SameLine();
  if (ImGui::RadioButton("side by side", !state.document.overlay)) state.document.overlay = false;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The takes and the result stand next to each other");
  ImGui::SameLine();
  if (ImGui::RadioButton("overlay", state.document.overlay)) state.document.overlay = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The takes and the result on the same spot, to compare poses");
  const bool view = ImGui::CollapsingHeader("View");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("What the 3D view shows");
  if (view) {
    ImGui::Checkbox("follow", &state.view.follow);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("The camera follows the skeletons as they walk");
    ImGui::SameLine();
    ImGui::Checkbox("labels", &state.view.labels);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Each take's name above its skeleton");
    ImGui::SameLine();
    ImGui::Checkbox("grid", &state.view.grid);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Lines on the floor");
    ImGui::Checkbox("shadows", &state.view.shadows);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Shadows of the skeletons on the floor");
    ImGui::SameLine();
    ImGui::Checkbox("contacts", &state.view.contacts);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Rings under the feet while they are planted on the floor");
  }
  ImGui::End();
}

}  // namespace mostyle::ui
