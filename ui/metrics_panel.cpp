#include "ui/metrics_panel.h"

#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "engine/kinematics/units.h"
#include "ui/layout.h"

namespace mostyle::ui {
namespace {
const ImVec4 kDimColor(0.60f, 0.62f, 0.66f, 1.0f);

// One row: a label in plain words (its tooltip says what it measures) and its value.
void row(const char* name, const std::string& value, const char* tooltip) {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextColored(kDimColor, "%s", name);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tooltip);
  ImGui::TableNextColumn();
  ImGui::TextUnformatted(value.c_str());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tooltip);
}

std::string milliseconds(double ms, const char* format = "%.1f ms") {
  if (ms < 0.0) return "-";
  char text[32];
  std::snprintf(text, sizeof text, format, ms);
  return text;
}

bool begin_table(const char* id) {
  if (!ImGui::BeginTable(id, 2, ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_BordersInnerV)) return false;
  ImGui::TableSetupColumn("what", ImGuiTableColumnFlags_WidthStretch, 1.5f);
  ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch, 1.0f);
  return true;
}
}  // namespace

double centimetres_per_unit(const std::string& unit_name) {
  // The names of engine/kinematics/units.cpp's bands.
  if (unit_name == "metres") return 100.0;
  if (unit_name == "feet") return 30.48;
  if (unit_name == "CMU units (1/0.45 inch)") return 2.54 / 0.45;
  if (unit_name == "inches") return 2.54;
  if (unit_name == "centimetres") return 1.0;
  if (unit_name == "millimetres") return 0.1;
  return 0.0;
}

std::string length_in_words(double value, double cm_per_unit, double height, const char* per) {
  char text[48];
  if (!std::isfinite(value) || value < 0.0) return "-";
  if (cm_per_unit > 0.0) {
    const double cm = value * cm_per_unit;
    if (cm >= 100.0) std::snprintf(text, sizeof text, "%.2f m%s", cm / 100.0, per);
    else if (cm >= 1.0) std::snprintf(text, sizeof text, "%.1f cm%s", cm, per);
    else std::snprintf(text, sizeof text, "%.1f mm%s", 10.0 * cm, per);
  } else if (height > 0.0) {
    std::snprintf(text, sizeof text, "%.2g%% of height%s", 100.0 * value / height, per);
  } else {
    return "-";
  }
  return text;
}

void MetricsPanel::draw(EditorState& state) {
  place_panel(PanelId::kMetrics, state);
  if (!ImGui::Begin(panel_title(PanelId::kMetrics))) {
    ImGui::End();
    return;
  }
  const PreparedPair* p = session_.snapshot().prepared.get();
  const DecomposedPair* d = session_.snapshot().decomposed.get();
  const BlendResult* b = session_.blend();
  if (p != unit_pair_) {  // a new pair: guess A's unit once (one pose of forward kinematics)
    unit_pair_ = p;
    cm_per_unit_ = height_ = 0.0;
    unit_name_.clear();
    if (p != nullptr && p->clip_a != nullptr) {
      const UnitsGuess guess = guess_units(*p->clip_a);
      unit_name_ = guess.name;
      height_ = guess.height;
      cm_per_unit_ = centimetres_per_unit(guess.name);
    }
  }
  auto length = [&](double value, const char* per = "") { return length_in_words(value, cm_per_unit_, height_, per); };
  if (p != nullptr) {
    ImGui::PushTextWrapPos(0.0f);
    if (cm_per_unit_ > 0.0)
      ImGui::TextColored(kDimColor, "Lengths in metric units; the file is in %s.", unit_name_.c_str());
    else
      ImGui::TextColored(kDimColor, "Unknown length unit: lengths as a share of A's height.");
    ImGui::PopTextWrapPos();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("BVH files do not say their unit: it is guessed from take A's height\n"
                        "(%.3g file units tall, taken to be a person of 1.5 to 1.9 m).", height_);
  }

  if (begin_table("##quality")) {
    row("Fit error A", d ? length(d->rmse_a) : "-",
        "How far A is from what the components rebuild of it (root mean square).\n"
        "Lower: the components hold more of A.");
    row("Fit error B", d ? length(d->rmse_b) : "-",
        "How far B is from what the components rebuild of it (root mean square).");
    row("Bone length, worst", b ? length(b->limb_length_max_error) : "-",
        "The most any bone of the blend differs from its length in A.");
    if (p) {
      row("Foot sliding A | B", length(p->foot_sliding_a, "/s") + " | " + length(p->foot_sliding_b, "/s"),
          "How fast planted feet slide over the floor, on average: A, and B on A's skeleton.");
    }
    if (b) {
      row("Foot sliding, blend", length(b->foot_sliding_raw, "/s") + " -> " + length(b->foot_sliding_cleaned, "/s"),
          "How fast the blend's planted feet slide: before -> after the foot lock\n(the same when foot lock is off).");
    }
    ImGui::EndTable();
  }
  // Timings differ run to run: a screenshot run (frame_ms < 0) shows none of them.
  if (session_.frame_ms < 0.0f) {
    ImGui::TextColored(kDimColor, "(timings hidden in screenshots)");
    ImGui::End();
    return;
  }
  if (begin_table("##times")) {
    row("Loading", milliseconds(p ? p->times.load_ms : -1.0), "Reading the two BVH files");
    row("Preparing", milliseconds(p ? p->times.preprocess_ms : -1.0),
        "Matching the skeletons, putting B on A's bones, facing and normalising");
    row("Time alignment", milliseconds(p ? p->times.dtw_ms : -1.0), "Matching the takes' steps in time (DTW)");
    row("Decomposition", milliseconds(d ? d->elapsed_ms : -1.0, "%.0f ms"),
        "Splitting the takes into components (on the worker, not in the way of the editor)");
    row("Synthesis", milliseconds(b ? b->synthesize_ms : -1.0, "%.3f ms"), "Making the blend from the components");
    row("Clean-up", milliseconds(b ? b->postprocess_ms : -1.0, "%.3f ms"), "Bone lengths and foot lock on the blend");
    row("Blend, all", milliseconds(b ? session_.blend_ms() : -1.0, "%.3f ms"),
        "The whole blend after a slider move, on the editor's thread");
    row("Export", milliseconds(session_.export_ms()), "The last BVH export");
    row("Frame, CPU", milliseconds(session_.frame_ms, "%.2f ms"), "Building one editor frame");
    row("Viewport, GPU", milliseconds(session_.viewport_ms, "%.2f ms"), "Drawing the 3D view");
    ImGui::EndTable();
  }
  ImGui::End();
}

}  // namespace mostyle::ui
