#include "ui/metrics_panel.h"

#include <cstdio>

#include <imgui.h>

#include "ui/layout.h"

namespace mostyle::ui {
namespace {
const ImVec4 kDimColor(0.60f, 0.62f, 0.66f, 1.0f);

void row(const char* name, const char* format, double value) {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextColored(kDimColor, "%s", name);
  ImGui::TableNextColumn();
  if (value < 0.0) ImGui::TextUnformatted("-");
  else ImGui::Text(format, value);
}
}  // namespace

void MetricsPanel::draw(EditorState& state) {
  place_next_window(Column::kRight, 0.81f, 0.19f);
  if (!ImGui::Begin("Metrics")) {
    ImGui::End();
    return;
  }
  (void)state;
  const PreparedPair* p = session_.snapshot().prepared.get();
  const DecomposedPair* d = session_.snapshot().decomposed.get();
  const BlendResult* b = session_.blend();
  const ImGuiTableFlags flags = ImGuiTableFlags_SizingStretchSame | ImGuiTableFlags_BordersInnerV;
  if (ImGui::BeginTable("##quality", 2, flags)) {
    row("RMSE A", "%.4g", d ? d->rmse_a : -1.0);
    row("RMSE B", "%.4g", d ? d->rmse_b : -1.0);
    row("bone length error", "%.3g", b ? b->limb_length_max_error : -1.0);
    if (p) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextColored(kDimColor, "foot sliding A | B");
      ImGui::TableNextColumn();
      ImGui::Text("%.3g | %.3g /s", p->foot_sliding_a, p->foot_sliding_b);
    }
    if (b) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextColored(kDimColor, "foot sliding blend");
      ImGui::TableNextColumn();
      ImGui::Text("%.3g -> %.3g /s", b->foot_sliding_raw, b->foot_sliding_cleaned);
    }
    ImGui::EndTable();
  }
  // Timings differ run to run: a screenshot run (frame_ms < 0) shows none of them.
  if (session_.frame_ms < 0.0f) {
    ImGui::TextColored(kDimColor, "(timings hidden in screenshots)");
    ImGui::End();
    return;
  }
  if (ImGui::BeginTable("##times", 2, flags)) {
    row("load", "%.1f ms", p ? p->times.load_ms : -1.0);
    row("preprocess", "%.1f ms", p ? p->times.preprocess_ms : -1.0);
    row("dtw", "%.1f ms", p ? p->times.dtw_ms : -1.0);
    row("decompose", "%.0f ms", d ? d->elapsed_ms : -1.0);
    row("synthesize", "%.3f ms", b ? b->synthesize_ms : -1.0);
    row("postprocess", "%.3f ms", b ? b->postprocess_ms : -1.0);
    row("blend (UI thread)", "%.3f ms", b ? session_.blend_ms() : -1.0);
    row("export", "%.1f ms", session_.export_ms());
    row("frame (CPU)", "%.2f ms", session_.frame_ms);
    row("viewport (GPU)", "%.2f ms", session_.viewport_ms);
    ImGui::EndTable();
  }
  ImGui::End();
}

}  // namespace mostyle::ui
