#include "ui/panels/parameters_panel.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <vector>

#include <imgui.h>

#include "ui/model/keyed_weights.h"
#include "ui/model/layer_parts.h"
#include "ui/panels/layout.h"
#include "ui/panels/range_slider.h"
#include "ui/panels/theme.h"

namespace mostyle::ui {

namespace {

// k and sparsity: the decomposition, recomputed when the slider is let go.
void draw_decomposition(DecompositionControls& p) {
  range_slider("components (k)", p.components, kComponentsRange);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("How many components the takes are split into. More: closer to the takes, less general.\n"
                      "Recomputed when you let go of the slider.");
  range_slider("sparsity", p.sparsity, kSparsityRange);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Share of the joints' channels each component may move (0.1: a tenth).\n"
                      "Small: each component is a small body part. Recomputed when you let go.");
}

// The decomposition's mode and how the takes are aligned in time. Paper mode, the paper's own
// synthesis, blends two takes: it is offered for two.
void draw_mode_and_alignment(DocumentControls& c, int takes) {
  int mode = c.mode == DecompositionMode::kShared ? 0 : 1;
  const bool two = takes == 2;
  if (two && ImGui::Combo("mode", &mode, "shared\0paper\0"))
    c.mode = mode == 0 ? DecompositionMode::kShared : DecompositionMode::kPaper;  // the engine link decomposes again
  if (two && ImGui::IsItemHovered())
    ImGui::SetTooltip("shared: one component set for A and B (alpha 1 is B)\npaper: separate decompositions, "
                      "cores blended (paper 3.6)");
  int align_on = static_cast<int>(c.align.on);
  if (ImGui::Combo("align on", &align_on, "auto\0left foot\0feet\0hands\0body\0")) {
    c.align.on = static_cast<AlignOn>(align_on);  // the engine link re-aligns
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("What the takes are matched in time on.\nauto: the left foot for walks and runs, "
                      "the joints that move most for other actions.");
  // One control for the time base and the warp: the paper's DTW always aligns whole takes.
  int method = c.align.method == DtwMethod::kPaper ? 2 : c.align.time_base == TimeBase::kCycles ? 0 : 1;
  if (ImGui::Combo("time warp", &method, "by cycles\0whole takes\0paper\0")) {
    c.align.method = method == 2 ? DtwMethod::kPaper : DtwMethod::kSlope;
    if (method < 2) c.align.time_base = method == 0 ? TimeBase::kCycles : TimeBase::kWhole;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("by cycles: each step cycle of the reference is matched with one of each other take (a short "
                      "take's reused in order), so all of the reference plays; where it stands or turns, the others "
                      "give their posture.\nwhole takes: one smooth match of the whole takes; extra material at the "
                      "ends is left out.\npaper: the paper's plain left-foot DTW, end to end, as published.");
}

// Foot lock, the timing, the seamless loop and components only, two to a line.
void draw_options(DocumentControls& c) {
  ImGui::Checkbox("foot lock", &c.foot_lock);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Pin planted feet in place so the result does not skate");
  ImGui::SameLine();
  ImGui::Checkbox("reference timing", &c.timing_a);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Off: the result's timing is mixed with the weights, as style is (a pair's moves from A's\n"
                      "at alpha 0 to B's at 1).\nOn: keep the reference take's (A's) timeline, to stay in sync with "
                      "other material.");
  ImGui::Checkbox("seamless loop", &c.loop);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Cut 1 to 4 whole gait cycles that play seamlessly on repeat (root travel kept).\n"
                      "Playback and export then use the loop.");
  ImGui::SameLine();
  bool components_only = !c.residual;
  if (ImGui::Checkbox("components only", &components_only)) c.residual = !components_only;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Off: each take's detail that the k components do not hold is mixed with the weights too,\n"
                      "so a take's whole weight gives exactly that take.\nOn: only what the components reconstruct "
                      "(the paper's synthesis); k and sparsity then shape the whole result.");
}

// Worker progress; the previous decomposition stays on screen until the new one arrives (the
// weights say why they are refused in the takes' panel, layers_panel.h).
void draw_status(const EngineLink& s, const Decomposed* d) {
  const WorkerStatus status = s.status();
  if (status.stage == WorkerStage::kLoading || status.stage == WorkerStage::kDecomposing) {
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "%s %.0f%%", worker_stage_name(status.stage), 100.0 * status.progress);
    ImGui::ProgressBar(status.progress, ImVec2(-1.0f, 0.0f), overlay);
  } else if (d != nullptr) {
    ImGui::TextColored(kDimColor, "shown: k %d, sparsity %.2f, %s", d->params.components, d->params.sparsity,
                       decomposition_mode_name(d->params.mode));
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("The decomposition the result uses now: %d components, sparsity %.2f, %s mode, %d iterations",
                        d->params.components, d->params.sparsity, decomposition_mode_name(d->params.mode), d->iterations);
  }
}

// One row of weights, one per take (a part's or a component's): each take's drag in its colour,
// the others following so that a mix's row sums to 1; in a transfer the styles' strengths only
// (the content's and the neutral's follow from them). Returns the row when one moved.
std::optional<std::vector<double>> draw_weight_row(const EditorState& state, std::vector<double> row) {
  const DocumentControls& c = state.document.controls;
  const int n = static_cast<int>(row.size());
  const int neutral = c.transfer ? transfer_neutral(c, n) : -1;
  bool moved = false;
  const float width = ImGui::CalcTextSize("-0.50").x + 2.0f * ImGui::GetStyle().FramePadding.x + ImGui::GetFontSize();
  for (int i = 0; i < n; ++i) {
    ImGui::PushID(i);
    if (i > 0) ImGui::SameLine();
    ImGui::SetNextItemWidth(width);
    double w = row[static_cast<size_t>(i)];
    if (c.transfer && (i == 0 || i == neutral)) {
      ImGui::TextColored(kDimColor, "%*s", 5, i == 0 ? "cont." : "neut.");
    } else if (range_drag("##w", w, c.transfer ? kStrengthRange : kMixWeightRange)) {
      if (c.transfer) row[static_cast<size_t>(i)] = w;
      else row = set_weight_keeping_sum(row, i, w);
      moved = true;
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%s", state.shown.size() > static_cast<size_t>(i) ? state.shown[static_cast<size_t>(i)].label.c_str() : "");
    ImGui::PopID();
  }
  if (!moved) return std::nullopt;
  return row;
}

// One row per part (legs, arms, spine): it sets every component of that part.
void draw_part_weights(EditorState& state, const Decomposed& d, const std::vector<double>& weights) {
  for (BodyPart part : kLayerParts) {
    const int first = first_component_of(d, part);
    if (first < 0) continue;
    ImGui::PushID(static_cast<int>(part));
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(body_part_name(part));
    ImGui::SameLine(90.0f);
    if (const auto row = draw_weight_row(state, component_row(state.document, first, weights))) {
      set_part_row(state.document, d, part, row);
      state.document.controls.per_part = true;
    }
    ImGui::PopID();
  }
}

// One row per component; the one hovered or held is the selected component.
void draw_component_weights(EditorState& state, const Decomposed& d, const std::vector<double>& weights) {
  DocumentControls& c = state.document.controls;
  ImGui::TextColored(kDimColor, "each component:");
  for (int i = 0; i < d.components(); ++i) {
    ImGui::PushID(1000 + i);
    ImGui::AlignTextToFramePadding();
    ImGui::Text("%s%s", d.component_joints[static_cast<size_t>(i)].name.c_str(), i == c.selected_component ? " *" : "");
    if (ImGui::IsItemHovered()) c.selected_component = i;
    ImGui::SameLine(90.0f);
    ImGui::BeginGroup();
    if (const auto row = draw_weight_row(state, component_row(state.document, i, weights))) {
      set_component_row(state.document, d, i, row);
      c.per_part = true;
    }
    ImGui::EndGroup();
    if (ImGui::IsItemHovered() || ImGui::IsItemActive()) c.selected_component = i;
    ImGui::PopID();
  }
}

// Shared mode: the takes' weights for each body part or component on their own.
void draw_body_parts(EditorState& state, const Decomposed* d, int takes) {
  DocumentControls& c = state.document.controls;
  const bool parts = ImGui::CollapsingHeader("Body parts");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Other weights for the legs, the arms, the spine, or each component");
  if (!parts) return;
  ImGui::Checkbox("weights per body part", &c.per_part);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("ShownMotion each body part's style from its own weights: legs from one take, arms from another.");
  if (d == nullptr || d->params.mode != DecompositionMode::kShared || takes < 1) return;
  if (ImGui::SmallButton("all = weights"))
    for (int i = 0; i < d->components(); ++i) set_component_row(state.document, *d, i, std::nullopt);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Every body part and component back to the takes' own weights");
  const std::vector<double> weights = weights_at_playhead(state, takes);
  draw_part_weights(state, *d, weights);
  draw_component_weights(state, *d, weights);
}

// Paper mode: the takes in levels of basic motions, and the level whose style comes from B.
void draw_basic_motions(DocumentControls& c, const DecompositionControls& p) {
  const bool basic = ImGui::CollapsingHeader("Basic motions", ImGuiTreeNodeFlags_DefaultOpen);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Paper mode: the takes in levels of motion, one level from B");
  if (!basic) return;
  range_slider("motion levels", c.basic_motions, kBasicMotionsRange);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Split each take into this many levels of basic motions (paper 3.5): level 1 holds the\n"
                      "most, each next level what the ones before left. 0: one decomposition.\n"
                      "Recomputed when you let go.");
  c.basic_sparsities.resize(static_cast<size_t>(c.basic_motions), p.sparsity);
  for (int i = 0; i < c.basic_motions; ++i) {
    ImGui::PushID(i);
    char label[32];
    std::snprintf(label, sizeof label, "level %d sparsity", i + 1);
    range_slider(label, c.basic_sparsities[static_cast<size_t>(i)], kSparsityRange);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Share of the channels each component of this level may move");
    ImGui::PopID();
  }
  if (c.basic_motions > 0) {
    // Shown from 1 like the levels above; stored from 0.
    range_slider("level from B", c.swap_level, swap_level_range(c.basic_motions), "%d", 1);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("The level whose style moves towards B with alpha (1: B's); the other levels stay A's");
  }
}

}  // namespace

void ParametersPanel::draw(EditorState& state) {
  place_panel(PanelId::kParameters, state);
  if (!ImGui::Begin(panel_title(PanelId::kParameters))) {
    ImGui::End();
    return;
  }
  EngineLink& s = engine_;
  DocumentControls& c = state.document.controls;
  DecompositionControls& p = state.document.parameters;
  const Decomposed* d = s.snapshot().decomposed.get();
  ImGui::PushItemWidth(-120.0f);  // room for the labels on the right

  // The takes' weights are in their own panel (layers_panel.h); here what is mixed and how.
  const int takes = s.takes() != nullptr ? s.takes()->size() : 0;
  draw_decomposition(p);
  draw_mode_and_alignment(c, takes);
  draw_options(c);
  draw_status(s, d);
  if (c.mode == DecompositionMode::kShared) draw_body_parts(state, d, takes);
  else draw_basic_motions(c, p);

  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace mostyle::ui
