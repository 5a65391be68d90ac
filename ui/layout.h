#pragma once
// Where the editor's windows start (ImGuiCond_FirstUseEver: the animator's own arrangement,
// saved in imgui.ini, wins afterwards). Left column: takes, parameters, files; right column:
// DTW, components, metrics; the viewport between them; the timeline along the bottom. Sizes
// follow the display, so 1280x720 fits and larger windows get larger panels.
#include <algorithm>

#include <imgui.h>

namespace mostyle::ui {

constexpr float kLayoutMargin = 12.0f;
constexpr float kTimelineReserve = 64.0f;  // the playback bar's height and margins

enum class Column { kLeft, kRight };

// top, height: fractions of the space above the timeline.
inline void place_next_window(Column column, float top, float height) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float width = column == Column::kLeft ? std::clamp(display.x * 0.235f, 280.0f, 420.0f)
                                              : std::clamp(display.x * 0.285f, 330.0f, 520.0f);
  const float x = column == Column::kLeft ? kLayoutMargin : display.x - width - kLayoutMargin;
  const float usable = std::max(200.0f, display.y - kTimelineReserve - kLayoutMargin);
  ImGui::SetNextWindowPos(ImVec2(x, kLayoutMargin + top * usable), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(width, height * usable - 8.0f), ImGuiCond_FirstUseEver);
}

}  // namespace mostyle::ui
