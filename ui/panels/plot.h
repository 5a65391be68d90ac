#pragma once
// Small line plots on ImGui's draw list (implot is not packaged): a framed area, curves scaled
// to it, a vertical playhead, and the mouse position in data coordinates.
#include <functional>

#include <imgui.h>

namespace mostyle::ui {

// A plot area placed at the cursor (width -1: the remaining width). Data x in [x0, x1] and y in
// [y0, y1] map onto it, y up.
struct PlotArea {
  ImVec2 min, max;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  bool hovered = false;
  bool clicked = false;

  ImVec2 to_screen(double x, double y) const;
  double x_at(float screen_x) const;
  double y_at(float screen_y) const;
};

// Reserves the area (an invisible button, so it takes clicks), draws its frame.
PlotArea begin_plot(const char* id, float width, float height, double x0, double x1, double y0, double y1);
// A polyline of n points given by `point(i, &x, &y)`, at most ~2 vertices per pixel column.
void plot_line(const PlotArea& area, int n, const std::function<void(int, double*, double*)>& point, ImU32 color,
               float thickness = 1.5f);
// A vertical line at data x.
void plot_vline(const PlotArea& area, double x, ImU32 color);
// A small text at the plot's top-left (legend line `row`).
void plot_legend(const PlotArea& area, int row, const char* text, ImU32 color);
// An axis's name, dim, inside the plot at its bottom-right corner (x: what runs across) or, with
// `left`, its bottom-left (what a left-hand axis counts).
void plot_axis_label(const PlotArea& area, const char* text, bool left = false);

// Colours shared by the plots: each take's and the result's, as in the viewport (take_color,
// result_color).
ImU32 take_color_u32(int take);
ImU32 color_blend();

}  // namespace mostyle::ui
