#include "ui/panels/palette_panel.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <imgui.h>

#include "engine/export/export_frames.h"
#include "engine/io/motion_file.h"
#include "engine/base/numbers.h"
#include "ui/model/document.h"
#include "ui/model/keyed_weights.h"
#include "ui/model/weight_keys_edit.h"
#include "ui/panels/keyed_tint.h"
#include "ui/panels/layout.h"
#include "ui/panels/fitted_text.h"
#include "ui/panels/range_slider.h"
#include "ui/panels/theme.h"

namespace mostyle::ui {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr const char* kTitle = "Style palette";
const char* const kPartNames[] = {"Legs", "Arms", "Spine, head"};  // short: the column is narrow at 1280 pixels
// The transfer's neutral choice that is no take: the change is measured from the content.
constexpr const char* kContentNeutral = "none: the content is its own neutral";

// Take i's label (ui: the animation's name, or the file's name without its extension) without the
// start every take's label shares up to
// a '_' or '-' ("cmu142_walk_happy", "cmu142_walk_marching": "happy", "marching"), so that
// names fit the narrow columns; the whole name is in the tooltips.
std::string name_of(const PreparedTakes& p, int i) {
  std::vector<std::string> sources;
  for (const PreparedTake& t : p.takes) sources.push_back(t.clip->source);
  return distinct_take_labels(sources)[static_cast<size_t>(i)];
}

ImU32 color_u32(int take) {
  const glm::vec3 c = take_color(take);
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f));
}

void swatch(int take) {
  const glm::vec3 c = take_color(take);
  ImGui::ColorButton("##swatch", ImVec4(c.r, c.g, c.b, 1.0f), ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
  ImGui::SameLine();
}

}  // namespace

std::vector<double> set_weight_keeping_sum(std::vector<double> w, int i, double value, double lo, double hi) {
  const int n = static_cast<int>(w.size());
  if (i < 0 || i >= n) return w;
  value = std::clamp(value, lo, hi);
  if (n == 1) {
    w[0] = 1.0;
    return w;
  }
  double others = 0.0;
  for (int j = 0; j < n; ++j)
    if (j != i) others += w[static_cast<size_t>(j)];
  const double rest = 1.0 - value;
  for (int j = 0; j < n; ++j) {
    if (j == i) continue;
    double& x = w[static_cast<size_t>(j)];
    x = std::abs(others) > 1e-9 ? x * rest / others : rest / (n - 1);
  }
  w[static_cast<size_t>(i)] = value;
  // Scaling may push another take out of range: clamp it and give the difference to take i.
  double sum = 0.0;
  for (int j = 0; j < n; ++j)
    if (j != i) {
      double& x = w[static_cast<size_t>(j)];
      x = std::clamp(x, lo, hi);
      sum += x;
    }
  w[static_cast<size_t>(i)] = 1.0 - sum;
  return w;
}

glm::vec2 pad_vertex(int take, int n) {
  const float angle = 2.0f * kPi * static_cast<float>(take) / static_cast<float>(std::max(n, 1));
  return glm::vec2(std::sin(angle), -std::cos(angle));
}

std::vector<double> pad_weights(glm::vec2 point, int n) {
  std::vector<double> w(static_cast<size_t>(n), 0.0);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const glm::vec2 d = point - pad_vertex(i, n);
    const double d2 = double(d.x) * d.x + double(d.y) * d.y;
    if (d2 < 1e-6) {  // on a vertex: that take alone
      std::fill(w.begin(), w.end(), 0.0);
      w[static_cast<size_t>(i)] = 1.0;
      return w;
    }
    w[static_cast<size_t>(i)] = 1.0 / d2;
    sum += w[static_cast<size_t>(i)];
  }
  for (double& x : w) x /= sum;
  return w;
}

glm::vec2 pad_point(const std::vector<double>& weights) {
  const int n = static_cast<int>(weights.size());
  glm::vec2 p(0.0f);
  for (int i = 0; i < n; ++i) p += static_cast<float>(weights[static_cast<size_t>(i)]) * pad_vertex(i, n);
  return p;
}

void PalettePanel::draw(EditorState& state) {
  const PreparedTakes* p = session_.palette();
  if (p == nullptr) return;  // the DTW view has the strip while a pair is loaded
  place_panel(PanelId::kDtw, state);
  if (!ImGui::Begin(kTitle)) {
    ImGui::End();
    return;
  }
  PaletteControls& c = state.document.controls.palette;
  const int n = p->size();
  // Each mode comes in on its own timing, as the command line gives it: a mix's timing mixed, a
  // transfer on its content's (the reference timing box changes it after).
  bool& reference_timing = state.document.controls.timing_a;
  if (ImGui::RadioButton("Mix", !c.transfer) && c.transfer) {
    c.transfer = false;
    reference_timing = false;
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Mix the takes' styles with one weight each (they sum to 1)");
  ImGui::SameLine();
  if (ImGui::RadioButton("Transfer", c.transfer) && !c.transfer) {
    c.transfer = true;
    reference_timing = true;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Put the change from a neutral take (or from the content itself) to styled takes onto the "
                      "reference (the content take), on the content's timing");
  ImGui::SameLine();
  ImGui::Checkbox("Ghosts", &c.ghosts);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Show every take beside the result, at the moment the result is in it");
  ImGui::SameLine();
  if (!c.transfer) {
    if (ImGui::SmallButton("Equal weights"))
      set_weights_at_playhead(state, n, std::vector<double>(static_cast<size_t>(n), 1.0 / n));
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Every take the same weight");
    ImGui::SameLine();
  }
  const ResultView& view = session_.result_view();
  if (const MixResult* m = view.mix()) {
    const std::string length = duration_in_words(motion_length_s(m->motion.world.rows(), p->fps));
    ImGui::TextColored(kDimColor, "%d takes, %s", n, length.c_str());
  }
  if (!view.error().empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(kErrorColor, "%s", view.error().c_str());
    ImGui::PopTextWrapPos();
  }
  if (c.transfer) draw_transfer(state, *p);
  else draw_mix(state, *p);
  ImGui::End();
}

void PalettePanel::draw_mix(EditorState& state, const PreparedTakes& p) {
  PaletteControls& c = state.document.controls.palette;
  const int n = p.size();
  // Keyed over time: the weights at the playhead; an edit keys them there (auto-key).
  const Keyed keyed = keyed_at_playhead(state, n);
  std::vector<double> weights = weights_at_playhead(state, n);
  bool moved = false;
  const float pad = std::clamp(ImGui::GetContentRegionAvail().y - 4.0f, 80.0f, 220.0f);
  // Compact rows, in as many columns as it takes for every take to show without scrolling (seven
  // takes in the strip of a 1280x720 window: two columns).
  const float row = ImGui::GetFontSize() + 2.0f * 1.0f + 2.0f;
  const int rows = std::max(1, static_cast<int>(pad / row));
  const int columns = std::clamp((n + rows - 1) / rows, 1, 4);
  if (ImGui::BeginTable("##mix", n >= 3 ? 3 : 2, ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn("weights", ImGuiTableColumnFlags_WidthStretch, 2.0f * static_cast<float>(columns));
    if (n >= 3) ImGui::TableSetupColumn("pad", ImGuiTableColumnFlags_WidthFixed, pad);
    ImGui::TableSetupColumn("parts", ImGuiTableColumnFlags_WidthStretch, columns > 1 ? 1.3f : 1.6f);
    ImGui::TableNextColumn();
    ImGui::BeginChild("##weights", ImVec2(0, pad));
    ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, ImVec2(ImGui::GetStyle().ItemSpacing.x, 2.0f));
    ImGui::PushStyleVar(ImGuiStyleVar_FramePadding, ImVec2(ImGui::GetStyle().FramePadding.x, 1.0f));
    const bool in_columns = columns > 1 && ImGui::BeginTable("##weight_columns", columns, ImGuiTableFlags_SizingStretchSame);
    for (int i = 0; i < n; ++i) {
      if (in_columns && i % columns == 0) ImGui::TableNextRow();
      if (in_columns) ImGui::TableNextColumn();
      ImGui::PushID(i);
      swatch(i);
      double w = weights[static_cast<size_t>(i)];
      // Room for a signed weight ("-0.35") whatever the panel's width; a drag, not a slider, so
      // that no knob covers the sign and a pixel moves the weight by 0.005.
      ImGui::SetNextItemWidth(ImGui::CalcTextSize("-0.50").x + 2.0f * ImGui::GetStyle().FramePadding.x +
                              (columns > 1 ? 0.5f : 2.0f) * ImGui::GetFontSize());
      {
        const KeyedTint tint(keyed);
        if (range_drag("##w", w, kMixWeightRange)) {
          weights = set_weight_keeping_sum(weights, i, w);
          moved = true;
        }
      }
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("How much of this take's style; the others follow so that the weights sum to 1 (from -0.5 "
                          "to 1.5: beyond 0 and 1 exaggerates).\nDrag sideways, or double-click and type%s",
                          keyed_hint(keyed));
      ImGui::SameLine();
      fitted_text(name_of(p, i), i == 0 ? " (ref.)" : "",
                  p.takes[static_cast<size_t>(i)].clip->source +
                      (i == 0 ? "\nThe reference: its skeleton, path and length lead" : ""));
      ImGui::PopID();
    }
    if (in_columns) ImGui::EndTable();
    ImGui::PopStyleVar(2);
    ImGui::EndChild();
    if (n >= 3) {
      ImGui::TableNextColumn();
      moved = draw_pad(weights, n) || moved;
    }
    ImGui::TableNextColumn();
    draw_parts(c, p);
    ImGui::EndTable();
  }
  if (moved) set_weights_at_playhead(state, n, weights);
}

bool PalettePanel::draw_pad(std::vector<double>& weights, int n) {
  const float size = ImGui::GetContentRegionAvail().x;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##pad", ImVec2(size, size));
  if (ImGui::IsItemHovered() && !ImGui::IsItemActive())
    ImGui::SetTooltip("Drag among the takes: the closer to a take, the more of its style");
  const float radius = 0.5f * size - 14.0f;
  const ImVec2 centre(origin.x + 0.5f * size, origin.y + 0.5f * size);
  auto screen = [&](glm::vec2 v) { return ImVec2(centre.x + radius * v.x, centre.y + radius * v.y); };
  const bool moved = ImGui::IsItemActive();
  if (moved) {
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    glm::vec2 v((mouse.x - centre.x) / radius, (mouse.y - centre.y) / radius);
    if (glm::length(v) > 1.0f) v = glm::normalize(v);
    weights = pad_weights(v, n);
  }
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddCircleFilled(centre, radius + 6.0f, IM_COL32(40, 42, 48, 255), 48);
  for (int i = 0; i < n; ++i) {
    draw->AddLine(screen(pad_vertex(i, n)), screen(pad_vertex((i + 1) % n, n)), IM_COL32(90, 92, 100, 255));
  }
  for (int i = 0; i < n; ++i) {
    const ImVec2 v = screen(pad_vertex(i, n));
    draw->AddCircleFilled(v, 6.0f, color_u32(i));
    char label[12];
    std::snprintf(label, sizeof label, "%d", i + 1);
    draw->AddText(ImVec2(v.x + 7.0f, v.y - 7.0f), IM_COL32(220, 220, 220, 255), label);
  }
  const ImVec2 marker = screen(pad_point(weights));
  draw->AddCircleFilled(marker, 5.0f, IM_COL32(130, 225, 118, 255));
  draw->AddCircle(marker, 8.0f, IM_COL32(255, 255, 255, 200), 20, 1.5f);
  return moved;
}

void PalettePanel::draw_parts(PaletteControls& c, const PreparedTakes& p) {
  const int n = p.size();
  ImGui::Checkbox("Per body part", &c.per_part);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Take a body part's style from one take (legs from one, arms from another); the rest follows "
                      "the weights");
  if (!c.per_part) return;
  c.part_weights.resize(std::size(kPartNames));
  for (size_t part = 0; part < std::size(kPartNames); ++part) {
    std::vector<double>& row = c.part_weights[part];
    int from = -1;  // -1: the weights
    for (int i = 0; i < n && static_cast<int>(row.size()) == n; ++i)
      if (row[static_cast<size_t>(i)] == 1.0) from = i;
    // The part's name, then the take it comes from in what is left of the column.
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(kPartNames[part]);
    ImGui::SameLine(ImGui::CalcTextSize(kPartNames[2]).x + ImGui::GetStyle().ItemSpacing.x);
    const float arrow = ImGui::GetFrameHeight() + 2.0f * ImGui::GetStyle().FramePadding.x;
    const float width = std::max(ImGui::GetContentRegionAvail().x, arrow + ImGui::GetFontSize());
    const std::string shown = fitted(from < 0 ? "weights" : name_of(p, from), width - arrow);
    ImGui::SetNextItemWidth(width);
    ImGui::PushID(static_cast<int>(part));
    if (ImGui::BeginCombo("##from", shown.c_str())) {
      if (ImGui::Selectable("the weights", from < 0)) row.clear();
      for (int i = 0; i < n; ++i)
        if (ImGui::Selectable(name_of(p, i).c_str(), from == i)) {
          row.assign(static_cast<size_t>(n), 0.0);
          row[static_cast<size_t>(i)] = 1.0;
        }
      ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Which take the style of the %s comes from (weights: the weights')",
                        part == 2 ? "spine and head" : part == 0 ? "legs" : "arms");
    ImGui::PopID();
  }
}

void PalettePanel::draw_transfer(EditorState& state, const PreparedTakes& p) {
  PaletteControls& c = state.document.controls.palette;
  const int n = p.size();
  if (static_cast<int>(c.strengths.size()) != n) c.strengths.assign(static_cast<size_t>(n), 1.0);
  c.neutral = std::clamp(c.neutral, 1, n - 1);
  swatch(0);
  ImGui::Text("Content: %s", name_of(p, 0).c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The take that keeps its skeleton, path and length and takes on the style (the first file; "
                      "open your own take first to make it the content)");
  ImGui::SameLine();
  if (ImGui::SmallButton("Make another take the content...")) ImGui::OpenPopup("##content");
  if (ImGui::BeginPopup("##content")) {
    for (int i = 1; i < n; ++i)
      if (ImGui::Selectable(name_of(p, i).c_str())) {
        // The content is the reference: the palette is prepared again with it first.
        // Every take keeps its weight and strength in its new place (ui/model/document.h).
        std::vector<std::string> files = session_.snapshot().paths;
        if (static_cast<size_t>(i) < files.size()) {
          std::vector<int> order(files.size());
          for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
          std::rotate(order.begin(), order.begin() + i, order.begin() + i + 1);
          std::rotate(files.begin(), files.begin() + i, files.begin() + i + 1);
          state.document = reorder_takes(state.document, order);
          state.document.controls.keys = reorder_keys(state.document.controls.keys, order);
          session_.load_files(files, WeightsOf::kNewTakes);
        }
      }
    ImGui::EndPopup();
  }
  // The neutral: a take, or none (the content is its own neutral: every other take is a style).
  const int neutral = transfer_neutral(c, n);
  ImGui::SetNextItemWidth(200.0f);
  if (ImGui::BeginCombo("Neutral", neutral == 0 ? kContentNeutral : name_of(p, neutral).c_str())) {
    if (ImGui::Selectable(kContentNeutral, neutral == 0)) c.content_neutral = true;
    for (int i = 1; i < n; ++i)
      if (ImGui::Selectable(name_of(p, i).c_str(), i == neutral)) {
        c.neutral = i;
        c.content_neutral = false;
      }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The take of the action without the style, or none: the change is from the content itself to "
                      "each style (one styled take is enough)");
  // Keyed over time: a style's strength is its weight at the playhead; an edit keys it there.
  const Keyed keyed = keyed_at_playhead(state, n);
  std::vector<double> weights = weights_at_playhead(state, n);
  bool moved = false;
  for (int i = 1; i < n; ++i) {
    if (i == neutral) continue;
    ImGui::PushID(i);
    swatch(i);
    ImGui::SetNextItemWidth(200.0f);
    {
      const KeyedTint tint(keyed);
      moved = range_slider("##strength", weights[static_cast<size_t>(i)], kStrengthRange) || moved;
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("How much of this style: 0 leaves the content as it is, 1 adds the whole change from the "
                        "%s to this one%s",
                        neutral == 0 ? "content" : "neutral take", keyed_hint(keyed));
    ImGui::SameLine();
    ImGui::Text("style: %s", name_of(p, i).c_str());
    ImGui::PopID();
  }
  if (moved) set_weights_at_playhead(state, n, transfer_mix_weights(weights, neutral, n));
}

}  // namespace mostyle::ui
