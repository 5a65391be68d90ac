#include "ui/panels/layers_panel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "engine/export/export_frames.h"
#include "engine/io/motion_file.h"
#include "engine/base/numbers.h"
#include "ui/model/document.h"
#include "ui/model/keyed_weights.h"
#include "ui/model/take_structure.h"
#include "ui/model/weight_keys_edit.h"
#include "ui/panels/alignment_view.h"
#include "ui/panels/fitted_text.h"
#include "ui/panels/keyed_tint.h"
#include "ui/panels/layout.h"
#include "ui/panels/plot.h"
#include "ui/panels/range_slider.h"
#include "ui/panels/structure_strip.h"
#include "ui/panels/theme.h"

namespace mostyle::ui {
namespace {

constexpr float kPi = 3.14159265358979f;
const char* const kPartNames[] = {"Legs", "Arms", "Spine, head"};  // short: the column is narrow at 1280 pixels
// The transfer's neutral choice that is no take: the change is measured from the content.
constexpr const char* kContentNeutral = "none: the content is its own neutral";

// The body parts' column: its checkbox whole, and a part's name beside a take's short name.
float parts_width() {
  const ImGuiStyle& style = ImGui::GetStyle();
  const float checkbox = ImGui::GetFrameHeight() + style.ItemInnerSpacing.x + ImGui::CalcTextSize("Per body part").x;
  return std::max(checkbox, ImGui::CalcTextSize("Spine, head").x + 7.0f * ImGui::GetFontSize());
}

void swatch(int take) {
  const glm::vec3 c = take_color(take);
  ImGui::ColorButton("##swatch", ImVec4(c.r, c.g, c.b, 1.0f), ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
  ImGui::SameLine();
}

// Take `take`'s own frames at the result's frames (frames_in_take of its sources: a registered
// take's frames back to its own, NaN where it gives its posture only); empty without a result.
Eigen::VectorXd own_frames_shown(const PreparedTakes& p, const MixResult* result, int take) {
  if (result == nullptr || result->sources.rows() == 0 || take >= result->sources.cols()) return {};
  return frames_in_take(p.takes[static_cast<size_t>(take)], result->sources.col(take));
}

// The take's own frames the result plays (lowest and highest), or none (first > last), and the one
// it shows at the playhead. shown: own_frames_shown.
struct Played {
  double first = 1.0, last = 0.0, now = -1.0;  // `now`: the frame shown at the playhead, -1 none
};
Played played_frames(const EditorState& state, const Eigen::VectorXd& shown) {
  Played out;
  out.first = INFINITY;
  out.last = -INFINITY;
  for (double f : shown)
    if (!std::isnan(f)) {
      out.first = std::min(out.first, f);
      out.last = std::max(out.last, f);
    }
  if (!state.shown.empty() && shown.size() > 0) {
    const int k = std::clamp(frame_at(state.shown.back(), state.playback.time_s), 0, static_cast<int>(shown.size()) - 1);
    if (!std::isnan(shown[k])) out.now = shown[k];
  }
  return out;
}

// The result's frame that shows the take's own frame nearest `frame`, or -1 when none does.
int output_frame_showing(const Eigen::VectorXd& shown, double frame) {
  int best = -1;
  double nearest = INFINITY;
  for (Eigen::Index k = 0; k < shown.size(); ++k)
    if (!std::isnan(shown[k]) && std::abs(shown[k] - frame) < nearest) {
      nearest = std::abs(shown[k] - frame);
      best = static_cast<int>(k);
    }
  return best;
}

// Take `take`'s own frames as a bar `size` wide at the cursor: its rests shaded, its actions
// lit, its strokes or gait cycles banded (every other one lighter, a tick where each begins), the
// frames the result plays outlined and the frame it shows at the playhead marked. Hover says
// what a frame is; a click moves the playhead to the result's frame that shows it.
void draw_take_timeline(EditorState& state, const PreparedTakes& p, int take, const MixResult* result, ImVec2 size) {
  const PreparedTake& t = p.takes[static_cast<size_t>(take)];
  const int frames = std::max(1, static_cast<int>(t.world.rows()));
  const ImVec2 at = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##timeline", size);
  const bool hovered = ImGui::IsItemHovered(), clicked = ImGui::IsItemClicked();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float top = at.y + 1.0f, bottom = at.y + size.y - 1.0f;
  auto x_of = [&](double frame) { return at.x + static_cast<float>(frame / frames) * size.x; };
  draw_structure_strip(t, ImVec2(at.x, top), ImVec2(at.x + size.x, bottom), frames, false, take_color_u32(take),
                       [](int f) { return double(f); });
  const Eigen::VectorXd shown = own_frames_shown(p, result, take);
  const Played played = played_frames(state, shown);
  if (played.first <= played.last)
    dl->AddRect(ImVec2(x_of(played.first), top), ImVec2(x_of(played.last + 1.0), bottom), IM_COL32(235, 235, 240, 200));
  if (played.now >= 0.0) {
    const float x = x_of(played.now + 0.5);
    dl->AddLine(ImVec2(x, at.y), ImVec2(x, at.y + size.y), IM_COL32(255, 255, 255, 255), 2.0f);
  }
  if (!hovered) return;
  const double frame = std::clamp(double(ImGui::GetIO().MousePos.x - at.x) / size.x * frames, 0.0, frames - 1.0);
  ImGui::SetTooltip("%s, frame %d of %d: %s\n%s\nclick: the result's frame that shows it",
                    short_take_name(p, take).c_str(), static_cast<int>(frame), frames,
                    frame_structure_words(t, static_cast<int>(frame)).c_str(),
                    played.first <= played.last
                        ? ("the result plays its frames " + std::to_string(static_cast<int>(played.first)) + " to " +
                           std::to_string(static_cast<int>(played.last)))
                              .c_str()
                        : "not played yet");
  const int output = output_frame_showing(shown, frame);
  if (clicked && output >= 0) state.playback.time_s = (output + 0.5) / p.fps;
}

}  // namespace

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

void LayersPanel::draw(EditorState& state) {
  const PreparedTakes* p = engine_.takes();
  place_panel(PanelId::kLayers, state);
  if (!ImGui::Begin(panel_title(PanelId::kLayers))) {
    ImGui::End();
    return;
  }
  if (p == nullptr) {
    ImGui::TextColored(kDimColor, "No takes loaded yet.");
    ImGui::End();
    return;
  }
  draw_mode(state, *p);
  if (state.document.controls.transfer) draw_transfer_takes(state, *p);
  if (ImGui::BeginTabBar("##layers")) {
    if (ImGui::BeginTabItem("Takes")) {
      draw_takes(state, *p);
      ImGui::EndTabItem();
    }
    aligned_take_ = std::clamp(aligned_take_, 1, std::max(1, p->size() - 1));
    const std::string tab = "Alignment: " + short_take_name(*p, aligned_take_) + "###alignment";
    if (ImGui::BeginTabItem(tab.c_str())) {
      draw_alignment_tab(state, *p);
      ImGui::EndTabItem();
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("How this take was matched in time to the reference (click a take's name to pick another)");
    ImGui::EndTabBar();
  }
  ImGui::End();
}

void LayersPanel::draw_mode(EditorState& state, const PreparedTakes& p) {
  DocumentControls& c = state.document.controls;
  const int n = p.size();
  // Each mode comes in on its own timing, as the command line gives it: a mix's timing mixed, a
  // transfer on its content's (the reference timing box changes it after).
  if (ImGui::RadioButton("Mix", !c.transfer) && c.transfer) {
    set_transfer(state.document, n, false);
    c.timing_a = false;
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Mix the takes' styles with one weight each (they sum to 1)");
  ImGui::SameLine();
  if (ImGui::RadioButton("Transfer", c.transfer) && !c.transfer) {
    set_transfer(state.document, n, true);
    c.timing_a = true;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Put the change from a neutral take (or from the content itself) to styled takes onto the "
                      "reference (the content take), which keeps its path, its timing and its planted feet");
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
  const ResultView& view = engine_.result_view();
  if (const MixResult* m = view.mix()) {
    const std::string length = duration_in_words(motion_length_s(m->motion.world.rows(), p.fps));
    ImGui::TextColored(kDimColor, "%d takes, %s", n, length.c_str());
  }
  if (!view.error().empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(kErrorColor, "%s", view.error().c_str());
    ImGui::PopTextWrapPos();
  }
}

void LayersPanel::draw_transfer_takes(EditorState& state, const PreparedTakes& p) {
  DocumentControls& c = state.document.controls;
  const int n = p.size();
  swatch(0);
  ImGui::Text("Content: %s", short_take_name(p, 0).c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The take that keeps its skeleton, path and length and takes on the style (the first file; "
                      "open your own take first to make it the content)");
  ImGui::SameLine();
  if (ImGui::SmallButton("Make another take the content...")) ImGui::OpenPopup("##content");
  if (ImGui::BeginPopup("##content")) {
    for (int i = 1; i < n; ++i)
      if (ImGui::Selectable(short_take_name(p, i).c_str())) {
        // The content is the reference: the takes are prepared again with it first.
        // Every take keeps its weight and strength in its new place (ui/model/document.h).
        std::vector<std::string> files = engine_.snapshot().paths;
        if (static_cast<size_t>(i) < files.size()) {
          std::vector<int> order(files.size());
          for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
          std::rotate(order.begin(), order.begin() + i, order.begin() + i + 1);
          std::rotate(files.begin(), files.begin() + i, files.begin() + i + 1);
          state.document = reorder_takes(state.document, order);
          state.document.controls.keys = reorder_keys(state.document.controls.keys, order);
          engine_.load_files(files, WeightsOf::kNewTakes);
        }
      }
    ImGui::EndPopup();
  }
  // The neutral: a take, or none (the content is its own neutral: every other take is a style);
  // a pair's B is its style, A its own neutral.
  if (!neutral_take_possible(n)) return;
  const int neutral = transfer_neutral(c, n);
  ImGui::SetNextItemWidth(200.0f);
  if (ImGui::BeginCombo("Neutral", neutral == 0 ? kContentNeutral : short_take_name(p, neutral).c_str())) {
    if (ImGui::Selectable(kContentNeutral, neutral == 0)) c.content_neutral = true;
    for (int i = 1; i < n; ++i)
      if (ImGui::Selectable(short_take_name(p, i).c_str(), i == neutral)) {
        c.neutral = i;
        c.content_neutral = false;
      }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The take of the action without the style, or none: the change is from the content itself to "
                      "each style (one styled take is enough)");
}

void LayersPanel::draw_takes(EditorState& state, const PreparedTakes& p) {
  const DocumentControls& c = state.document.controls;
  const int n = p.size();
  // Keyed over time: the weights at the playhead; an edit keys them there (auto-key).
  std::vector<double> weights = weights_at_playhead(state, n);
  bool moved = false;
  const float room = std::max(ImGui::GetContentRegionAvail().y - 4.0f, 60.0f);
  // The pad square, at most a fifth of the width: the rows' names and timelines need the rest.
  const float pad = std::clamp(std::min(room, 0.2f * ImGui::GetContentRegionAvail().x), 80.0f, 220.0f);
  if (ImGui::BeginTable("##takes", c.transfer ? 1 : 3, ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn("rows", ImGuiTableColumnFlags_WidthStretch);
    if (!c.transfer) {
      ImGui::TableSetupColumn("pad", ImGuiTableColumnFlags_WidthFixed, pad);
      ImGui::TableSetupColumn("parts", ImGuiTableColumnFlags_WidthFixed, parts_width());
    }
    ImGui::TableNextColumn();
    ImGui::BeginChild("##rows", ImVec2(0, room));
    ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, ImVec2(ImGui::GetStyle().ItemSpacing.x, 2.0f));
    ImGui::PushStyleVar(ImGuiStyleVar_FramePadding, ImVec2(ImGui::GetStyle().FramePadding.x, 1.0f));
    for (int i = 0; i < n; ++i) moved = draw_row(state, p, i, weights) || moved;
    ImGui::PopStyleVar(2);
    ImGui::EndChild();
    if (!c.transfer) {
      ImGui::TableNextColumn();
      moved = draw_pad(weights, n) || moved;
      ImGui::TableNextColumn();
      draw_parts(state, p);
    }
    ImGui::EndTable();
  }
  if (moved) {
    if (c.transfer) weights = transfer_mix_weights(weights, transfer_neutral(c, n), n);
    set_weights_at_playhead(state, n, weights);
  }
}

bool LayersPanel::draw_row(EditorState& state, const PreparedTakes& p, int take, std::vector<double>& weights) {
  const DocumentControls& c = state.document.controls;
  const int n = p.size();
  const Keyed keyed = keyed_at_playhead(state, n);
  const int neutral = c.transfer ? transfer_neutral(c, n) : -1;
  bool moved = false;
  ImGui::PushID(take);
  swatch(take);
  double w = weights[static_cast<size_t>(take)];
  // Room for a signed weight ("-0.35") whatever the panel's width; a drag, not a slider, so that
  // no knob covers the sign and a pixel moves the weight by 0.005.
  const float field = ImGui::CalcTextSize("-0.50").x + 2.0f * ImGui::GetStyle().FramePadding.x + 2.0f * ImGui::GetFontSize();
  ImGui::SetNextItemWidth(field);
  if (c.transfer && (take == 0 || take == neutral)) {
    ImGui::AlignTextToFramePadding();
    ImGui::TextColored(kDimColor, "%-9s", take == 0 ? "content" : "neutral");
    ImGui::SameLine(0.0f, 0.0f);
    ImGui::Dummy(ImVec2(std::max(0.0f, field - ImGui::CalcTextSize("content  ").x), 1.0f));
  } else {
    {
      const KeyedTint tint(keyed);
      const bool edited = c.transfer ? range_drag("##strength", w, kStrengthRange) : range_drag("##w", w, kMixWeightRange);
      if (edited) {
        if (c.transfer) weights[static_cast<size_t>(take)] = w;
        else weights = set_weight_keeping_sum(weights, take, w);
        moved = true;
      }
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(c.transfer ? "How much of this style: 0 leaves the content as it is, 1 adds the whole change "
                                     "from the neutral take (or the content) to this one%s"
                                   : "How much of this take's style; the others follow so that the weights sum to 1 "
                                     "(from -0.5 to 1.5: beyond 0 and 1 exaggerates).\nDrag sideways, or double-click "
                                     "and type%s",
                        keyed_hint(keyed));
  }
  ImGui::SameLine();
  // The name (a pair's A and B before it), in a column of its own; a click picks its alignment.
  const float name_w = std::min(12.0f * ImGui::GetFontSize(), 0.4f * ImGui::GetContentRegionAvail().x);
  const std::string letter = take_letter(take, n);
  const std::string name = (letter.empty() ? "" : letter + "  ") + short_take_name(p, take) + (take == 0 ? " (ref.)" : "");
  const bool picked = take == aligned_take_;
  if (ImGui::Selectable((fitted(name, name_w) + "###name").c_str(), picked && take > 0, 0, ImVec2(name_w, 0.0f)) &&
      take > 0)
    aligned_take_ = take;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s%s", p.takes[static_cast<size_t>(take)].clip->source.c_str(),
                      take == 0 ? "\nThe reference: its skeleton, path and length lead"
                                : "\nClick: its alignment onto the reference in the Alignment tab");
  ImGui::SameLine();
  const float bar_w = std::max(ImGui::GetContentRegionAvail().x, 40.0f);
  draw_take_timeline(state, p, take, engine_.result(), ImVec2(bar_w, ImGui::GetFrameHeight()));
  ImGui::PopID();
  return moved;
}

bool LayersPanel::draw_pad(std::vector<double>& weights, int n) {
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
    draw->AddCircleFilled(v, 6.0f, take_color_u32(i));
    char label[12];
    std::snprintf(label, sizeof label, "%d", i + 1);
    draw->AddText(ImVec2(v.x + 7.0f, v.y - 7.0f), IM_COL32(220, 220, 220, 255), label);
  }
  const ImVec2 marker = screen(pad_point(weights));
  draw->AddCircleFilled(marker, 5.0f, IM_COL32(130, 225, 118, 255));
  draw->AddCircle(marker, 8.0f, IM_COL32(255, 255, 255, 200), 20, 1.5f);
  return moved;
}

void LayersPanel::draw_parts(EditorState& state, const PreparedTakes& p) {
  const int n = p.size();
  DocumentControls& c = state.document.controls;
  ImGui::Checkbox("Per body part", &c.per_part);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("ShownMotion a body part's style from one take (legs from one, arms from another); the rest follows "
                      "the weights");
  const Decomposed* d = engine_.snapshot().decomposed.get();
  if (!c.per_part || d == nullptr || d->shared() == nullptr) return;
  for (size_t part = 0; part < std::size(kPartNames); ++part) {
    const BodyPart body_part = kLayerParts[part];
    const int from = part_from_take(state.document, *d, body_part);  // -1: the weights
    // The part's name, then the take it comes from in what is left of the column.
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(kPartNames[part]);
    ImGui::SameLine(ImGui::CalcTextSize(kPartNames[2]).x + ImGui::GetStyle().ItemSpacing.x);
    const float arrow = ImGui::GetFrameHeight() + 2.0f * ImGui::GetStyle().FramePadding.x;
    const float width = std::max(ImGui::GetContentRegionAvail().x, arrow + ImGui::GetFontSize());
    const std::string shown = fitted(from < 0 ? "weights" : short_take_name(p, from), width - arrow);
    ImGui::SetNextItemWidth(width);
    ImGui::PushID(static_cast<int>(part));
    if (ImGui::BeginCombo("##from", shown.c_str())) {
      if (ImGui::Selectable("the weights", from < 0)) set_part_row(state.document, *d, body_part, std::nullopt);
      for (int i = 0; i < n; ++i)
        if (ImGui::Selectable(short_take_name(p, i).c_str(), from == i)) {
          std::vector<double> row(static_cast<size_t>(n), 0.0);
          row[static_cast<size_t>(i)] = 1.0;
          set_part_row(state.document, *d, body_part, row);
        }
      ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Which take the style of the %s comes from (weights: the weights')", body_part_name(body_part));
    ImGui::PopID();
  }
}

void LayersPanel::draw_alignment_tab(EditorState& state, const PreparedTakes& p) {
  if (imaged_ != &p || imaged_take_ != aligned_take_) {
    image_ = dtw_cost_image(p, aligned_take_);
    imaged_ = &p;
    imaged_take_ = aligned_take_;
  }
  draw_alignment(state, p, aligned_take_, engine_.result(), image_);
}

}  // namespace mostyle::ui
