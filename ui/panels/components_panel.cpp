#include "ui/panels/components_panel.h"
#include "ui/panels/theme.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "ui/panels/layout.h"
#include "ui/panels/plot.h"

namespace mostyle::ui {
namespace {

// The style palette: its shared components by body part, with their joints.
void draw_palette_components(const Decomposed& pd, const PreparedTakes& palette) {
  ImGui::TextColored(kDimColor, "%d components shared by %d takes", pd.components(), palette.size());
  ImGui::PushTextWrapPos(0.0f);
  for (const ComponentJoints& cj : pd.component_joints) {
    std::string joints;
    for (int column : cj.columns) joints += (joints.empty() ? "" : ", ") + palette.takes.front().names[static_cast<size_t>(column)];
    ImGui::Text("%s", cj.name.c_str());
    ImGui::SameLine();
    ImGui::TextColored(kDimColor, "%s", joints.c_str());
  }
  ImGui::PopTextWrapPos();
}

// The component picked (c.selected_component): a combo of the components by their plain names
// ("left leg 2", from the body region they move), and previous and next.
void draw_picker(DocumentControls& c, const Decomposed& d) {
  const int k = d.components();
  ImGui::SetNextItemWidth(140.0f);
  auto name_of = [&](int i) {
    return i >= 0 && i < static_cast<int>(d.component_joints.size()) ? d.component_joints[static_cast<size_t>(i)].name
                                                                     : std::string("none");
  };
  if (ImGui::BeginCombo("component", name_of(c.selected_component).c_str())) {
    if (ImGui::Selectable("none", c.selected_component < 0)) c.selected_component = -1;
    for (int i = 0; i < k; ++i) {
      ImGui::PushID(i);
      if (ImGui::Selectable(name_of(i).c_str(), c.selected_component == i)) c.selected_component = i;
      ImGui::PopID();
    }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Pick a component: its joints light up on the blend");
  ImGui::SameLine();
  if (ImGui::ArrowButton("##prev", ImGuiDir_Left)) c.selected_component = std::max(-1, c.selected_component - 1);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Previous component");
  ImGui::SameLine();
  if (ImGui::ArrowButton("##next", ImGuiDir_Right)) c.selected_component = std::min(k - 1, c.selected_component + 1);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Next component");
}

// The joints component `sel` moves (lit on the blend skeleton), when it is one.
void draw_joints(const PreparedTakes& p, const Decomposed& d, int sel) {
  if (sel < 0 || sel >= d.support.rows()) return;
  std::string joints;
  for (size_t j = 0; j < p.takes[0].names.size() && 3 * j + 2 < static_cast<size_t>(d.support.cols()); ++j) {
    const Eigen::Index col = 3 * static_cast<Eigen::Index>(j);
    if (d.support(sel, col) != 0 || d.support(sel, col + 1) != 0 || d.support(sel, col + 2) != 0)
      joints += (joints.empty() ? "" : ", ") + p.takes[0].names[j];
  }
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextColored(kDimColor, "joints: %s", joints.empty() ? "(none)" : joints.c_str());
  ImGui::PopTextWrapPos();
}

// Component `sel`'s weights in A and B over A's timeline; a click moves the playhead there.
void draw_weights(EditorState& state, const PreparedTakes& p, const Decomposed& d, int sel) {
  const bool shared = d.params.mode == BlendMode::kShared;
  const Eigen::MatrixXd* wa = shared ? &d.shared()->stacked.weights[0] : &d.paper()->a.weights;
  const Eigen::MatrixXd* wb = shared ? &d.shared()->stacked.weights[1] : &d.paper()->b.weights;
  const float plot_h = std::max(50.0f, (ImGui::GetContentRegionAvail().y - 2.0f * ImGui::GetTextLineHeightWithSpacing()) * 0.5f);
  if (sel >= 0 && sel < wa->cols() && sel < wb->cols() && wa->rows() > 1) {
    const double top = std::max({1e-9, wa->col(sel).cwiseAbs().maxCoeff(), wb->col(sel).cwiseAbs().maxCoeff()});
    PlotArea w = begin_plot("##weights", -1.0f, plot_h, 0.0, static_cast<double>(wa->rows() - 1), -1.05 * top, 1.05 * top);
    plot_line(w, static_cast<int>(wa->rows()), [&](int i, double* x, double* y) { *x = i; *y = (*wa)(i, sel); }, color_a());
    plot_line(w, static_cast<int>(wb->rows()), [&](int i, double* x, double* y) { *x = i; *y = (*wb)(i, sel); }, color_b());
    plot_vline(w, frame_at(state.takes.front(), state.playback.time_s), IM_COL32(255, 255, 255, 140));
    plot_legend(w, 0, "weight in A", color_a());
    plot_legend(w, 1, "weight in B", color_b());
    if (w.hovered) ImGui::SetTooltip("How much of this component A and B use over time; click: jump there");
    if (w.clicked) state.playback.time_s = (std::clamp(w.x_at(ImGui::GetIO().MousePos.x), 0.0, 1e9) + 0.5) / p.fps;
  } else {
    ImGui::TextColored(kDimColor, "Pick a component to see its joints and weights.");
  }
}

// The fit error of A and B against k, a point per decomposition tried; hover: the nearest.
void draw_fit_error_plot(const std::vector<const ErrorPoint*>& points) {
  double top = 1e-9;
  int kmax = 1;
  for (const ErrorPoint* e : points) {
    top = std::max({top, e->rmse_a, e->rmse_b});
    kmax = std::max(kmax, e->components);
  }
  PlotArea r = begin_plot("##rmse", -1.0f, std::max(40.0f, ImGui::GetContentRegionAvail().y - 4.0f), 0.0, kmax + 1, 0.0,
                          1.1 * top);
  const int n = static_cast<int>(points.size());
  plot_line(r, n, [&](int i, double* x, double* y) { *x = points[static_cast<size_t>(i)]->components; *y = points[static_cast<size_t>(i)]->rmse_a; }, color_a());
  plot_line(r, n, [&](int i, double* x, double* y) { *x = points[static_cast<size_t>(i)]->components; *y = points[static_cast<size_t>(i)]->rmse_b; }, color_b());
  ImDrawList* dl = ImGui::GetWindowDrawList();
  for (const ErrorPoint* e : points) {
    dl->AddCircleFilled(r.to_screen(e->components, e->rmse_a), 3.0f, color_a());
    dl->AddCircleFilled(r.to_screen(e->components, e->rmse_b), 3.0f, color_b());
  }
  if (r.hovered) {
    const ErrorPoint* nearest = points.front();
    const double k = r.x_at(ImGui::GetIO().MousePos.x);
    for (const ErrorPoint* e : points)
      if (std::abs(e->components - k) < std::abs(nearest->components - k)) nearest = e;
    ImGui::SetTooltip("%d components\nfit error A %.4g\nfit error B %.4g (file units)", nearest->components,
                      nearest->rmse_a, nearest->rmse_b);
  }
}

// Reconstruction error against k, from every decomposition seen with this mode and sparsity.
void draw_fit_error(const BlendSession& session, const Decomposed& d) {
  std::vector<const ErrorPoint*> points;
  for (const ErrorPoint& e : session.error_curve())
    if (e.mode == d.params.mode && e.sparsity == d.params.sparsity) points.push_back(&e);
  ImGui::Text("Fit error by k (sparsity %.2f)", d.params.sparsity);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("How far what the components rebuild is from each take (root mean square, file units),\n"
                      "for each number of components tried so far: the curve flattens where more stop helping.");
  if (points.empty()) return;
  ImGui::SameLine();
  if (session.sweeping()) ImGui::TextColored(kDimColor, "computing...");
  else ImGui::TextColored(kDimColor, "%d to %d", points.front()->components, points.back()->components);
  draw_fit_error_plot(points);
}

}  // namespace

void ComponentsPanel::draw(EditorState& state) {
  place_panel(PanelId::kComponents, state);
  if (!ImGui::Begin(panel_title(PanelId::kComponents))) {
    ImGui::End();
    return;
  }
  const PreparedTakes* p = session_.pair();
  const Decomposed* d = session_.snapshot().decomposed.get();
  DocumentControls& c = state.document.controls;
  if (const Decomposed* pd = session_.palette() != nullptr ? session_.snapshot().decomposed.get() : nullptr) {
    draw_palette_components(*pd, *session_.palette());
    ImGui::End();
    return;
  }
  if (p == nullptr || d == nullptr) {
    ImGui::TextColored(kDimColor, session_.palette() ? "Waiting for the palette's decomposition..."
                                                     : "Waiting for the decomposition...");
    ImGui::End();
    return;
  }
  draw_picker(c, *d);
  // Its joints (lit on the blend skeleton) and its weights over A's timeline.
  const int sel = c.selected_component;
  draw_joints(*p, *d, sel);
  draw_weights(state, *p, *d, sel);
  draw_fit_error(session_, *d);
  ImGui::End();
}

}  // namespace mostyle::ui
