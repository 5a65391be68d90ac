#include "ui/panels/components_panel.h"
#include "ui/panels/theme.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "engine/io/motion_file.h"

#include "ui/panels/layout.h"
#include "ui/panels/plot.h"

namespace mostyle::ui {
namespace {

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

// Take i's name in the plots' legends: a pair's A and B, else its label.
std::string legend_name(const PreparedTakes& p, int i) {
  const char* letter = take_letter(i, p.size());
  return *letter ? letter : take_label(p.takes[static_cast<size_t>(i)].clip->source);
}

// Take i's weights of the components (frames x k, on the common timeline), or null in paper mode
// past its two takes.
const Eigen::MatrixXd* take_weights_of(const Decomposed& d, int i) {
  if (const SharedComponents* shared = d.shared()) return &shared->stacked.weights[static_cast<size_t>(i)];
  if (i > 1) return nullptr;
  return i == 0 ? &d.paper()->a.weights : &d.paper()->b.weights;
}

// Component `sel`'s weight in each take over the common timeline; a click moves the playhead there.
void draw_weights(EditorState& state, const PreparedTakes& p, const Decomposed& d, int sel) {
  const float plot_h = std::max(50.0f, (ImGui::GetContentRegionAvail().y - 2.0f * ImGui::GetTextLineHeightWithSpacing()) * 0.5f);
  const Eigen::MatrixXd* first = take_weights_of(d, 0);
  if (sel < 0 || first == nullptr || sel >= first->cols() || first->rows() <= 1) {
    ImGui::TextColored(kDimColor, "Pick a component to see its joints and weights.");
    return;
  }
  double top = 1e-9;
  for (int i = 0; i < p.size(); ++i)
    if (const Eigen::MatrixXd* w = take_weights_of(d, i)) top = std::max(top, w->col(sel).cwiseAbs().maxCoeff());
  PlotArea w = begin_plot("##weights", -1.0f, plot_h, 0.0, static_cast<double>(first->rows() - 1), -1.05 * top, 1.05 * top);
  for (int i = 0; i < p.size(); ++i) {
    const Eigen::MatrixXd* x = take_weights_of(d, i);
    if (x == nullptr) continue;
    plot_line(w, static_cast<int>(x->rows()), [&](int f, double* px, double* py) { *px = f; *py = (*x)(f, sel); },
              take_color_u32(i));
    if ((i + 1) * ImGui::GetTextLineHeight() < plot_h)  // as many legends as the plot has room for
      plot_legend(w, i, ("weight in " + legend_name(p, i)).c_str(), take_color_u32(i));
  }
  plot_vline(w, frame_at(state.shown.front(), state.playback.time_s), IM_COL32(255, 255, 255, 140));
  if (w.hovered) ImGui::SetTooltip("How much of this component each take uses over time; click: jump there");
  if (w.clicked) state.playback.time_s = (std::clamp(w.x_at(ImGui::GetIO().MousePos.x), 0.0, 1e9) + 0.5) / p.fps;
}

// Each take's fit error against k, a point per decomposition tried; hover: the nearest.
void draw_fit_error_plot(const PreparedTakes& p, const std::vector<const ErrorPoint*>& points) {
  double top = 1e-9;
  int kmax = 1;
  for (const ErrorPoint* e : points) {
    for (double r : e->rmse) top = std::max(top, r);
    kmax = std::max(kmax, e->components);
  }
  PlotArea r = begin_plot("##rmse", -1.0f, std::max(40.0f, ImGui::GetContentRegionAvail().y - 4.0f), 0.0, kmax + 1, 0.0,
                          1.1 * top);
  const int n = static_cast<int>(points.size());
  ImDrawList* dl = ImGui::GetWindowDrawList();
  for (int take = 0; take < p.size(); ++take) {
    auto error_at = [&](int i) {
      const std::vector<double>& rmse = points[static_cast<size_t>(i)]->rmse;
      return static_cast<size_t>(take) < rmse.size() ? rmse[static_cast<size_t>(take)] : 0.0;
    };
    plot_line(r, n, [&](int i, double* x, double* y) { *x = points[static_cast<size_t>(i)]->components; *y = error_at(i); },
              take_color_u32(take));
    for (int i = 0; i < n; ++i)
      dl->AddCircleFilled(r.to_screen(points[static_cast<size_t>(i)]->components, error_at(i)), 3.0f, take_color_u32(take));
  }
  if (r.hovered) {
    const ErrorPoint* nearest = points.front();
    const double k = r.x_at(ImGui::GetIO().MousePos.x);
    for (const ErrorPoint* e : points)
      if (std::abs(e->components - k) < std::abs(nearest->components - k)) nearest = e;
    std::string lines = std::to_string(nearest->components) + " components";
    for (size_t take = 0; take < nearest->rmse.size() && take < static_cast<size_t>(p.size()); ++take) {
      char line[96];
      std::snprintf(line, sizeof line, "\nfit error %s %.4g", legend_name(p, static_cast<int>(take)).c_str(),
                    nearest->rmse[take]);
      lines += line;
    }
    ImGui::SetTooltip("%s (file units)", lines.c_str());
  }
}

// Reconstruction error against k, from every decomposition seen with this mode and sparsity.
void draw_fit_error(const EngineLink& engine, const PreparedTakes& p, const Decomposed& d) {
  std::vector<const ErrorPoint*> points;
  for (const ErrorPoint& e : engine.error_curve())
    if (e.mode == d.params.mode && e.sparsity == d.params.sparsity) points.push_back(&e);
  ImGui::Text("Fit error by k (sparsity %.2f)", d.params.sparsity);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("How far what the components rebuild is from each take (root mean square, file units),\n"
                      "for each number of components tried so far: the curve flattens where more stop helping.");
  if (points.empty()) return;
  ImGui::SameLine();
  if (engine.sweeping()) ImGui::TextColored(kDimColor, "computing...");
  else ImGui::TextColored(kDimColor, "%d to %d", points.front()->components, points.back()->components);
  draw_fit_error_plot(p, points);
}

}  // namespace

void ComponentsPanel::draw(EditorState& state) {
  place_panel(PanelId::kComponents, state);
  if (!ImGui::Begin(panel_title(PanelId::kComponents))) {
    ImGui::End();
    return;
  }
  const PreparedTakes* p = engine_.takes();
  const Decomposed* d = p != nullptr ? engine_.snapshot().decomposed.get() : nullptr;
  DocumentControls& c = state.document.controls;
  if (d == nullptr) {
    ImGui::TextColored(kDimColor, "Waiting for the decomposition...");
    ImGui::End();
    return;
  }
  ImGui::TextColored(kDimColor, "%d components shared by %d takes", d->components(), p->size());
  draw_picker(c, *d);
  // Its joints (lit on the result's skeleton), its weight in each take over time, the fit error.
  const int sel = c.selected_component;
  draw_joints(*p, *d, sel);
  draw_weights(state, *p, *d, sel);
  draw_fit_error(engine_, *p, *d);
  ImGui::End();
}

}  // namespace mostyle::ui
