#include "ui/panels/parameters_panel.h"

#include <algorithm>
#include <cstdio>

#include <imgui.h>

#include "ui/model/keyed_weights.h"
#include "ui/panels/keyed_tint.h"
#include "ui/panels/layout.h"
#include "ui/panels/range_slider.h"
#include "ui/panels/theme.h"

namespace mostyle::ui {

namespace {

// A pair's alpha: keyed over time, the value at the playhead, and moving it keys it there
// (auto-key). In transfer mode it is the strength of B's style put on A.
void draw_alpha(EditorState& state) {
  const Keyed keyed = keyed_at_playhead(state, 2);
  const bool transfer = state.document.controls.palette.transfer;
  double alpha = weights_at_playhead(state, 2)[1];
  bool moved = false;
  {
    const KeyedTint tint(keyed);
    moved = range_slider(transfer ? "strength###alpha" : "alpha###alpha", alpha, kAlphaRange);
  }
  if (moved) set_weights_at_playhead(state, 2, pair_weights(alpha));  // blended this frame
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s Applied immediately.%s",
                      transfer ? "0 leaves A as it is, 1 puts B's whole style on A." : "0: style A, 1: style B.",
                      keyed_hint(keyed));
}

// A pair's mode: a blend of A and B, or a transfer of B's style onto A, A its own neutral (the
// command line's `transfer A --style B`): A keeps its path, its pace and its timeline.
void draw_pair_transfer(DocumentControls& c) {
  bool transfer = c.palette.transfer;
  if (ImGui::Checkbox("put B's style on A", &transfer)) {
    c.palette.transfer = transfer;
    if (transfer) c.palette.content_neutral = true;  // a pair has no other take to be the neutral
    c.timing_a = transfer;                           // as the palette's Transfer button does
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("On: A is your own take and B a style. A keeps its path, its timing and its planted\n"
                      "feet's pace, and takes on B's style as far as the strength says.\n"
                      "Off: a blend between A and B, their paths and timing mixed too.");
}

// k and sparsity: the decomposition, recomputed when the slider is let go.
void draw_decomposition(BlendParameters& p) {
  range_slider("components (k)", p.components, kComponentsRange);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("How many components the takes are split into. More: closer to the takes, less general.\n"
                      "Recomputed when you let go of the slider.");
  range_slider("sparsity", p.sparsity, kSparsityRange);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Share of the joints' channels each component may move (0.1: a tenth).\n"
                      "Small: each component is a small body part. Recomputed when you let go.");
}

// The blend mode (a pair's) and how the takes are aligned in time.
void draw_mode_and_alignment(DocumentControls& c, bool palette) {
  int mode = c.mode == BlendMode::kShared ? 0 : 1;
  if (!palette && ImGui::Combo("mode", &mode, "shared\0paper\0"))
    c.mode = mode == 0 ? BlendMode::kShared : BlendMode::kPaper;  // the engine link decomposes again
  if (!palette && ImGui::IsItemHovered())
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
void draw_options(DocumentControls& c, bool palette) {
  ImGui::Checkbox("foot lock", &c.foot_lock);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Pin planted feet in place so the result does not skate");
  ImGui::SameLine();
  ImGui::Checkbox(palette ? "reference timing" : "A's timing", &c.timing_a);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s", palette ? "Off: the mix's timing is mixed with the weights, as style is.\n"
                                      "On: keep the reference take's timeline, to stay in sync with other material."
                                    : "Off: the blend's timing moves from A's (alpha 0) to B's (alpha 1), as style does.\n"
                                      "On: keep A's timeline, to stay in sync with other material.");
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

// Worker progress; the previous decomposition stays on screen until the new one arrives. Then a
// pair's result error (a palette's weights say theirs in the palette panel).
void draw_status(const BlendSession& s, const Decomposed* d, bool palette) {
  const WorkerStatus status = s.status();
  if (status.stage == WorkerStage::kLoading || status.stage == WorkerStage::kDecomposing) {
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "%s %.0f%%", worker_stage_name(status.stage), 100.0 * status.progress);
    ImGui::ProgressBar(status.progress, ImVec2(-1.0f, 0.0f), overlay);
  } else if (d != nullptr) {
    ImGui::TextColored(kDimColor, "shown: k %d, sparsity %.2f, %s", d->params.components, d->params.sparsity,
                       blend_mode_name(d->params.mode));
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("The decomposition the result uses now: %d components, sparsity %.2f, %s mode, %d iterations",
                        d->params.components, d->params.sparsity, blend_mode_name(d->params.mode), d->iterations);
  }
  if (!palette && !s.result_error().empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(kErrorColor, "%s", s.result_error().c_str());
    ImGui::PopTextWrapPos();
  }
}

// One slider per part (legs, arms, spine): it sets every component of that part.
void draw_part_alphas(DocumentControls& c, const Decomposed& d) {
  for (BodyPart part : {BodyPart::kLegs, BodyPart::kArms, BodyPart::kSpine}) {
    int first = -1;
    for (int i = 0; i < d.components(); ++i)
      if (part_covers(part, d.component_joints[static_cast<size_t>(i)].region)) {
        first = i;
        break;
      }
    if (first < 0) continue;
    double a = c.component_alpha[static_cast<size_t>(first)];
    if (range_slider(body_part_name(part), a, kAlphaRange)) {
      for (int i = 0; i < d.components(); ++i)
        if (part_covers(part, d.component_joints[static_cast<size_t>(i)].region))
          c.component_alpha[static_cast<size_t>(i)] = a;
      c.per_component = true;
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("This body part's style: 0 from A, 1 from B (sets all its components)");
  }
}

// One slider per component; the one hovered or held is the selected component.
void draw_component_alphas(DocumentControls& c, const Decomposed& d) {
  ImGui::TextColored(kDimColor, "each component:");
  for (int i = 0; i < d.components(); ++i) {
    ImGui::PushID(i);
    double a = c.component_alpha[static_cast<size_t>(i)];
    char label[64];
    std::snprintf(label, sizeof label, "%s%s", d.component_joints[static_cast<size_t>(i)].name.c_str(),
                  i == c.selected_component ? " *" : "");
    if (range_slider(label, a, kAlphaRange)) {
      c.component_alpha[static_cast<size_t>(i)] = a;
      c.per_component = true;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("This component's style: 0 from A, 1 from B (its joints light up)");
    if (ImGui::IsItemHovered() || ImGui::IsItemActive()) c.selected_component = i;
    ImGui::PopID();
  }
}

// Shared mode: a different alpha for each body part or component.
void draw_body_parts(DocumentControls& c, double alpha, const Decomposed* d) {
  const bool parts = ImGui::CollapsingHeader("Body parts");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("A different alpha for the legs, the arms, the spine, or each component");
  if (!parts) return;
  ImGui::Checkbox("alpha per body part", &c.per_component);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Take each body part's style from A or B on its own: legs from one, arms from the other.");
  if (d == nullptr || d->params.mode != BlendMode::kShared) return;
  c.component_alpha.resize(static_cast<size_t>(d->components()), alpha);
  if (ImGui::SmallButton("all = alpha")) std::fill(c.component_alpha.begin(), c.component_alpha.end(), alpha);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Set every body part and component back to the main alpha");
  draw_part_alphas(c, *d);
  draw_component_alphas(c, *d);
}

// Paper mode: the takes in levels of basic motions, and the level whose style comes from B.
void draw_basic_motions(DocumentControls& c, const BlendParameters& p) {
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
  BlendSession& s = session_;
  DocumentControls& c = state.document.controls;
  BlendParameters& p = state.document.parameters;
  const Decomposed* d = s.snapshot().decomposed.get();
  ImGui::PushItemWidth(-120.0f);  // room for the labels on the right

  // With the style palette loaded, its panel holds the weights; alpha, the mode and the body
  // parts' alphas are the pair's.
  const bool palette = s.palette() != nullptr;
  if (!palette) {
    draw_alpha(state);
    draw_pair_transfer(c);
  }
  draw_decomposition(p);
  draw_mode_and_alignment(c, palette);
  draw_options(c, palette);
  draw_status(s, d, palette);
  if (c.mode == BlendMode::kShared && !palette) draw_body_parts(c, pair_alpha(state.document), d);
  else if (!palette) draw_basic_motions(c, p);

  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace mostyle::ui
