#include "ui/panels/plot.h"

#include "ui/model/result_view.h"

#include <algorithm>
#include <cmath>

namespace mostyle::ui {

ImVec2 PlotArea::to_screen(double x, double y) const {
  const double u = x1 != x0 ? (x - x0) / (x1 - x0) : 0.5;
  const double v = y1 != y0 ? (y - y0) / (y1 - y0) : 0.5;
  return ImVec2(min.x + static_cast<float>(u) * (max.x - min.x), max.y - static_cast<float>(v) * (max.y - min.y));
}

double PlotArea::x_at(float screen_x) const {
  const double u = (screen_x - min.x) / std::max(1.0f, max.x - min.x);
  return x0 + u * (x1 - x0);
}

double PlotArea::y_at(float screen_y) const {
  const double v = (max.y - screen_y) / std::max(1.0f, max.y - min.y);
  return y0 + v * (y1 - y0);
}

PlotArea begin_plot(const char* id, float width, float height, double x0, double x1, double y0, double y1) {
  PlotArea a;
  if (width <= 0.0f) width = std::max(32.0f, ImGui::GetContentRegionAvail().x);
  a.min = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton(id, ImVec2(width, height));
  a.max = ImVec2(a.min.x + width, a.min.y + height);
  a.hovered = ImGui::IsItemHovered();
  a.clicked = ImGui::IsItemClicked(ImGuiMouseButton_Left) || (ImGui::IsItemActive() && ImGui::IsMouseDragging(0));
  a.x0 = x0;
  a.x1 = x1;
  a.y0 = y0;
  a.y1 = y1;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(a.min, a.max, IM_COL32(22, 24, 28, 255));
  dl->AddRect(a.min, a.max, IM_COL32(70, 74, 82, 255));
  return a;
}

void plot_line(const PlotArea& area, int n, const std::function<void(int, double*, double*)>& point, ImU32 color,
               float thickness) {
  if (n < 2) return;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->PushClipRect(area.min, area.max, true);
  const int pixels = std::max(2, static_cast<int>(area.max.x - area.min.x) * 2);
  const int step = std::max(1, n / pixels);
  ImVec2 previous;
  for (int i = 0, k = 0; i < n; i += step, ++k) {
    double x = 0, y = 0;
    point(i, &x, &y);
    const ImVec2 p = area.to_screen(x, y);
    if (k > 0) dl->AddLine(previous, p, color, thickness);
    previous = p;
  }
  dl->PopClipRect();
}

void plot_vline(const PlotArea& area, double x, ImU32 color) {
  const float sx = area.to_screen(x, 0.0).x;
  if (sx < area.min.x || sx > area.max.x) return;
  ImGui::GetWindowDrawList()->AddLine(ImVec2(sx, area.min.y), ImVec2(sx, area.max.y), color, 1.0f);
}

void plot_legend(const PlotArea& area, int row, const char* text, ImU32 color) {
  const ImVec2 at(area.min.x + 4.0f, area.min.y + 2.0f + row * ImGui::GetFontSize());
  const ImVec2 size = ImGui::CalcTextSize(text);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(ImVec2(at.x - 2.0f, at.y), ImVec2(at.x + size.x + 2.0f, at.y + size.y), IM_COL32(22, 24, 28, 200));
  dl->AddText(at, color, text);
}

void plot_axis_label(const PlotArea& area, const char* text, bool left) {
  const ImVec2 size = ImGui::CalcTextSize(text);
  const ImVec2 at(left ? area.min.x + 4.0f : area.max.x - size.x - 4.0f, area.max.y - size.y - 2.0f);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(ImVec2(at.x - 2.0f, at.y), ImVec2(at.x + size.x + 2.0f, at.y + size.y), IM_COL32(22, 24, 28, 200));
  dl->AddText(at, IM_COL32(160, 164, 172, 255), text);
}

ImU32 take_color_u32(int take) {
  const glm::vec3 c = take_color(take);
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f));
}
ImU32 color_blend() { return IM_COL32(128, 224, 117, 255); }

}  // namespace mostyle::ui
