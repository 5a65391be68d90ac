#pragma once
// Text in a narrow place: cut to the width there is, with "..." where it was cut, so that a long
// take name never runs under the next column or out of its panel; the whole text on hover.
#include <string>

#include <imgui.h>

namespace mostyle::ui {

// `text` as it fits `width` pixels in the current font: whole when it fits, else its longest
// start that fits with "..." after it ("..." alone when nothing more fits). O(length).
inline std::string fitted(const std::string& text, float width) {
  if (ImGui::CalcTextSize(text.c_str()).x <= width) return text;
  const float dots = ImGui::CalcTextSize("...").x;
  size_t keep = text.size();
  while (keep > 0 && ImGui::CalcTextSize(text.c_str(), text.c_str() + keep).x + dots > width) --keep;
  return text.substr(0, keep) + "...";
}

// Draws `text` fitted to what is left of the line, `suffix` (" (ref.)") always whole after it;
// the whole text on hover, with `more` below it when not empty.
inline void fitted_text(const std::string& text, const std::string& suffix = "", const std::string& more = "") {
  const float room = ImGui::GetContentRegionAvail().x - ImGui::CalcTextSize(suffix.c_str()).x;
  ImGui::TextUnformatted((fitted(text, room) + suffix).c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s%s%s", (text + suffix).c_str(), more.empty() ? "" : "\n", more.c_str());
}

}  // namespace mostyle::ui
