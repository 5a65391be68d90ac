#include "ui/dtw_panel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "ui/layout.h"
#include "ui/plot.h"

namespace mostyle::ui {
namespace {
constexpr int kMatchLines = 40;  // lines joining matched frames in the "before" plot

// B's signal value at fractional frame t (linear).
double sample(const Eigen::MatrixXd& signal, double t, int column) {
  const double last = static_cast<double>(signal.rows() - 1);
  t = std::clamp(t, 0.0, last);
  const int i = static_cast<int>(std::floor(t));
  const int k = std::min(i + 1, static_cast<int>(last));
  const double u = t - i;
  return (1.0 - u) * signal(i, column) + u * signal(k, column);
}

// Heat colour for a normalised cost: dark blue (low) to warm yellow (high).
ImU32 heat(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  const float r = std::min(1.0f, 1.6f * v), g = std::pow(v, 1.6f) * 0.95f, b = 0.35f + 0.4f * (1.0f - v) - 0.3f * v;
  return ImGui::ColorConvertFloat4ToU32(ImVec4(0.08f + 0.9f * r, 0.06f + g, std::max(0.05f, b), 1.0f));
}

// The path step for A frame i (the first one; the path is monotone).
std::pair<int, int> match_of(const DtwPath& path, int i) {
  auto it = std::lower_bound(path.steps.begin(), path.steps.end(), std::make_pair(i, -1));
  if (it == path.steps.end()) return path.steps.empty() ? std::make_pair(i, 0) : path.steps.back();
  return *it;
}
}  // namespace

void DtwPanel::draw(EditorState& state) {
  place_next_window(Column::kRight, 0.0f, 0.54f);
  if (!ImGui::Begin("DTW alignment")) {
    ImGui::End();
    return;
  }
  const PreparedPair* p = session_.snapshot().prepared.get();
  if (p == nullptr || p->signal_a.rows() < 2 || p->signal_b.rows() < 2 || p->path.steps.empty()) {
    ImGui::TextColored(ImVec4(0.6f, 0.62f, 0.66f, 1.0f), "No pair aligned yet.");
    ImGui::End();
    return;
  }
  SessionControls& c = session_.controls();
  const int fa = static_cast<int>(p->signal_a.rows()), fb = static_cast<int>(p->signal_b.rows());
  ImGui::SetNextItemWidth(110.0f);
  ImGui::Combo("left foot", &c.dtw_coordinate, "lateral x\0height y\0forward z\0");
  ImGui::SameLine();
  ImGui::TextColored(ImVec4(0.6f, 0.62f, 0.66f, 1.0f), "cost %.3g  %d x %d", p->path.cost, fa, fb);
  const int col = std::clamp(c.dtw_coordinate, 0, static_cast<int>(p->signal_a.cols()) - 1);

  const double lo = std::min(p->signal_a.col(col).minCoeff(), p->signal_b.col(col).minCoeff());
  double hi = std::max(p->signal_a.col(col).maxCoeff(), p->signal_b.col(col).maxCoeff());
  if (hi <= lo) hi = lo + 1.0;
  const double span = hi - lo;
  const int current = state.takes.empty() ? 0 : frame_at(state.takes[kTakeA], state.playback.time_s);
  const float line = ImGui::GetTextLineHeightWithSpacing();
  const float plot_h = std::max(50.0f, (ImGui::GetContentRegionAvail().y - 2.0f * line) * 0.36f);
  int hovered_i = -1;

  // Before warping: A above, B below, each on its own timeline; matched frames joined.
  ImGui::TextUnformatted("before warping: matched frames joined");
  const int frames = std::max(fa, fb);
  PlotArea before = begin_plot("##before", -1.0f, plot_h, 0.0, frames - 1, lo - 1.15 * span, hi + 0.1 * span);
  {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->PushClipRect(before.min, before.max, true);
    const size_t n = p->path.steps.size();
    const size_t stride = std::max<size_t>(1, n / kMatchLines);
    for (size_t s = 0; s < n; s += stride) {
      const auto [i, j] = p->path.steps[s];
      dl->AddLine(before.to_screen(i, p->signal_a(i, col)), before.to_screen(j, p->signal_b(j, col) - 1.05 * span),
                  IM_COL32(150, 155, 165, 90), 1.0f);
    }
    dl->PopClipRect();
  }
  plot_line(before, fa, [&](int i, double* x, double* y) { *x = i; *y = p->signal_a(i, col); }, color_a());
  plot_line(before, fb, [&](int j, double* x, double* y) { *x = j; *y = p->signal_b(j, col) - 1.05 * span; }, color_b());
  plot_legend(before, 0, "A", color_a());
  plot_legend(before, 1, "B", color_b());
  if (before.hovered) hovered_i = std::clamp(static_cast<int>(std::lround(before.x_at(ImGui::GetIO().MousePos.x))), 0, fa - 1);
  if (before.clicked && hovered_i >= 0) state.playback.time_s = (hovered_i + 0.5) / p->fps;

  // Below: the cost matrix (A frames down, B frames across, the optimal path and the playhead
  // on it) beside the signals after warping (B resampled onto A's timeline, on top of A).
  const float side = std::clamp(std::min(ImGui::GetContentRegionAvail().y - line - 4.0f,
                                         0.5f * ImGui::GetContentRegionAvail().x),
                                60.0f, 600.0f);
  ImGui::BeginGroup();
  ImGui::TextUnformatted("cost and path");
  const DtwCostImage& img = session_.dtw_image();
  PlotArea cost = begin_plot("##cost", side, side, 0.0, fb, fa, 0.0);  // y down: frame 0 at the top
  if (img.rows > 0 && img.cols > 0) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float cw = (cost.max.x - cost.min.x) / img.cols, ch = (cost.max.y - cost.min.y) / img.rows;
    for (int r = 0; r < img.rows; ++r)
      for (int k = 0; k < img.cols; ++k)
        dl->AddRectFilled(ImVec2(cost.min.x + k * cw, cost.min.y + r * ch),
                          ImVec2(cost.min.x + (k + 1) * cw + 0.5f, cost.min.y + (r + 1) * ch + 0.5f), heat(img.cost(r, k)));
    const size_t n = p->path.steps.size();
    plot_line(cost, static_cast<int>(n),
              [&](int s, double* x, double* y) {
                *x = p->path.steps[static_cast<size_t>(s)].second + 0.5;
                *y = p->path.steps[static_cast<size_t>(s)].first + 0.5;
              },
              IM_COL32(255, 255, 255, 230), 2.0f);
    const auto [ci, cj] = match_of(p->path, current);
    dl->AddCircleFilled(cost.to_screen(cj + 0.5, ci + 0.5), 4.5f, color_blend());
  }
  ImGui::EndGroup();
  ImGui::SameLine();
  ImGui::BeginGroup();
  ImGui::TextUnformatted("after warping");
  PlotArea after = begin_plot("##after", -1.0f, side, 0.0, fa - 1, lo - 0.08 * span, hi + 0.08 * span);
  plot_line(after, fa, [&](int i, double* x, double* y) { *x = i; *y = p->signal_a(i, col); }, color_a(), 2.0f);
  if (p->warp.size() == fa)
    plot_line(after, fa, [&](int i, double* x, double* y) { *x = i; *y = sample(p->signal_b, p->warp[i], col); },
              color_b());
  plot_vline(after, current, IM_COL32(255, 255, 255, 140));
  plot_legend(after, 0, "A", color_a());
  plot_legend(after, 1, "B warped", color_b());
  if (after.hovered) hovered_i = std::clamp(static_cast<int>(std::lround(after.x_at(ImGui::GetIO().MousePos.x))), 0, fa - 1);
  if (after.clicked && hovered_i >= 0) state.playback.time_s = (hovered_i + 0.5) / p->fps;
  ImGui::EndGroup();
  if (cost.hovered) {
    hovered_i = std::clamp(static_cast<int>(cost.y_at(ImGui::GetIO().MousePos.y)), 0, fa - 1);
    if (cost.clicked) state.playback.time_s = (hovered_i + 0.5) / p->fps;
  }
  if (hovered_i >= 0) {
    const auto [i, j] = match_of(p->path, hovered_i);
    ImGui::SetTooltip("A frame %d  <->  B frame %d\nclick: jump there", i, j);
  }
  ImGui::End();
}

}  // namespace mostyle::ui
