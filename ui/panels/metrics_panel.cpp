#include "ui/panels/metrics_panel.h"
#include "ui/panels/theme.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <imgui.h>

#include "engine/io/motion_file.h"
#include "engine/base/numbers.h"
#include "engine/kinematics/units.h"
#include "ui/panels/fitted_text.h"
#include "ui/panels/layout.h"

namespace mostyle::ui {
namespace {

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
  ImGui::TableSetupColumn("what", ImGuiTableColumnFlags_WidthStretch, 1.0f);
  ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch, 1.3f);
  return true;
}
}  // namespace

Metrics gather_metrics(const EngineLink& engine, bool transfer) {
  Metrics m;
  const WorkerSnapshot& snapshot = engine.snapshot();
  const PreparedTakes* p = snapshot.prepared.get();
  if (p == nullptr) return m;
  const Decomposed* d = snapshot.decomposed.get();
  m.reference = p->takes.front().clip.get();
  m.result = result_name(p->size(), transfer);
  // A pair's takes by their letters, more by what tells their names apart (a narrow column).
  std::vector<std::string> sources;
  for (const PreparedTake& take : p->takes) sources.push_back(take.clip->source);
  m.take_names = distinct_take_labels(sources);
  for (int i = 0; i < p->size(); ++i)
    if (*take_letter(i, p->size())) m.take_names[static_cast<size_t>(i)] = take_letter(i, p->size());
  m.load_ms = snapshot.times.load_ms;
  m.preprocess_ms = snapshot.times.preprocess_ms;
  m.dtw_ms = snapshot.times.dtw_ms;
  if (d != nullptr) m.decompose_ms = snapshot.times.decompose_ms;
  // The result shown (a blend, mix or transfer), made on this thread.
  const ResultView& view = engine.result_view();
  m.measures = mix_measures(*p, d, view.mix(), !view.previewing());
  if (view.mix() != nullptr) {
    const StageTimes& times = view.mix_times();
    m.synthesize_ms = times.synthesize_ms;
    m.postprocess_ms = times.postprocess_ms;
    m.result_ms = view.mix_ms();
  }
  return m;
}

void MetricsPanel::draw(EditorState& state) {
  place_panel(PanelId::kMetrics, state);
  if (!ImGui::Begin(panel_title(PanelId::kMetrics))) {
    ImGui::End();
    return;
  }
  draw_live_table();
  const Metrics m = gather_metrics(engine_, state.document.controls.transfer);
  guess_unit(m.reference);
  const char* letter = take_letter(0, static_cast<int>(m.take_names.size()));
  const std::string reference = *letter ? std::string("take ") + letter : "the reference take";
  if (m.reference != nullptr) draw_unit_note(reference.c_str());
  draw_takes_table(m);
  draw_quality_table(m, reference.c_str());
  // Timings differ run to run: a screenshot run (frame_ms < 0) shows none of them.
  if (state.times.frame_ms < 0.0f) {
    ImGui::TextColored(kDimColor, "(timings hidden in screenshots)");
    ImGui::End();
    return;
  }
  draw_times_table(m, state.times);
  ImGui::End();
}

void MetricsPanel::guess_unit(const Clip* reference) {
  if (reference == unit_clip_) return;
  // A new reference: guess its unit once (one pose of forward kinematics).
  unit_clip_ = reference;
  cm_per_unit_ = height_ = 0.0;
  unit_name_.clear();
  if (reference != nullptr) {
    const UnitsGuess guess = guess_units(*reference);
    unit_name_ = guess.name;
    height_ = guess.height;
    cm_per_unit_ = centimetres_per_unit(guess.name);
  }
}

std::string MetricsPanel::length(double value, const char* per) const {
  return length_in_words(value, cm_per_unit_, height_, per);
}

void MetricsPanel::draw_unit_note(const char* reference) {
  ImGui::PushTextWrapPos(0.0f);
  if (cm_per_unit_ > 0.0)
    ImGui::TextColored(kDimColor, "Lengths in metric units; the file is in %s.", unit_name_.c_str());
  else
    ImGui::TextColored(kDimColor, "Unknown length unit: lengths as a share of %s's height.", reference);
  ImGui::PopTextWrapPos();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("BVH files do not say their unit: it is guessed from %s's height\n"
                      "(%.3g file units tall, taken to be a person of 1.5 to 1.9 m).", reference, height_);
}

void MetricsPanel::draw_takes_table(const Metrics& m) {
  // Per take: its fit error and foot sliding, one row each (names clipped to the column, whole
  // on hover).
  if (!ImGui::BeginTable("##takes", 3, ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_BordersInnerV)) return;
  // The numbers' columns as wide as "10.6 cm/s"; the names have the rest.
  const float number = ImGui::CalcTextSize("10.6 cm/s").x + ImGui::GetStyle().CellPadding.x * 2.0f;
  ImGui::TableSetupColumn("take", ImGuiTableColumnFlags_WidthStretch, 1.0f);
  ImGui::TableSetupColumn("fit", ImGuiTableColumnFlags_WidthFixed, number);
  ImGui::TableSetupColumn("planted", ImGuiTableColumnFlags_WidthFixed, number);
  ImGui::TableHeadersRow();
  for (size_t i = 0; i < m.measures.takes.size() && i < m.take_names.size(); ++i) {
    const TakeMeasures& t = m.measures.takes[i];
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::PushStyleColor(ImGuiCol_Text, kDimColor);
    fitted_text(m.take_names[i]);  // cut with "..." in the narrow column, whole on hover
    ImGui::PopStyleColor();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(t.fit_error ? length(*t.fit_error).c_str() : "-");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Fit error: how far this take is from what the components rebuild of it (root mean\n"
                        "square). Lower: the components hold more of it.");
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(planted_speed(t.planted_speed, m.measures.body_height).c_str());
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("How fast this take's planted feet move over the floor, on average, in %% of the body's\n"
                        "height per second: its ankles and toes while within 3%% of the body's height of their\n"
                        "floor (on the reference's skeleton), as mostyle-cli reports it.");
  }
  ImGui::EndTable();
}

std::string MetricsPanel::planted_speed(double value, double body_height) {
  if (!(body_height > 0.0)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.2f%%h/s", 100.0 * value / body_height);
  return text;
}

void MetricsPanel::draw_quality_table(const Metrics& m, const char* reference) {
  if (!begin_table("##quality")) return;
  const std::optional<ResultMeasures>& r = m.measures.result;
  const double body = m.measures.body_height;
  // A multiple of the takes' ("1.02x the takes'"), "-" without a result or where theirs is 0.
  auto times_takes = [&r](std::optional<double> (ResultMeasures::*ratio)() const) {
    const std::optional<double> x = r ? ((*r).*ratio)() : std::nullopt;
    if (!x) return std::string("-");
    char text[48];
    std::snprintf(text, sizeof text, "%.2fx the takes'", *x);
    return std::string(text);
  };
  const std::string bones = "The most any bone of the " + m.result + " differs from its length in " + reference + ".";
  row("Bone length, worst", r ? length(r->limb_length_max_error) : "-", bones.c_str());
  const std::string fastest_tip = "How fast the " + m.result + "'s fastest joint moves (its 99.9th percentile over the frames), as\n"
                                  "a multiple of the fastest of the takes it mixes: well over 1x is a pop.";
  row("Fastest joint", times_takes(&ResultMeasures::fastest_ratio), fastest_tip.c_str());
  // Planted feet as mostyle-cli reports them: the result's against the takes' own, in the body's
  // height per second (a mean in cm/s reads as sliding where it is the measure's floor).
  const std::string ratio_tip = "How fast the " + m.result + "'s planted feet move after the foot lock, as a multiple of\n"
                                "the takes' own (weighted as the " + m.result + " weights them; a transfer: its content's).\n"
                                "1x or under: no more sliding than the takes have.";
  row("Planted feet", times_takes(&ResultMeasures::planted_ratio), ratio_tip.c_str());
  const std::string tip = "How fast the " + m.result + "'s planted feet move, measured as each take's are, in % of\n"
                          "the body's height per second: before -> after the foot lock (the same when it is off).";
  row("  result", r ? planted_speed(r->planted_raw, body) + " -> " + planted_speed(r->planted_cleaned, body) : "-",
      tip.c_str());
  row("  takes", r ? planted_speed(r->planted_inputs, body) : "-",
      "How fast the takes' own planted feet move, weighted as mixed, in % of the body's height per second");
  ImGui::EndTable();
}

void MetricsPanel::draw_times_table(const Metrics& m, const FrameTimes& times) {
  if (!begin_table("##times")) return;
  row("Loading", milliseconds(m.load_ms), "Reading the takes' files");
  row("Preparing", milliseconds(m.preprocess_ms),
      "Matching the skeletons, putting every take on the reference's bones, facing and normalising");
  row("Time alignment", milliseconds(m.dtw_ms), "Matching the takes' steps in time (DTW)");
  row("Decomposition", milliseconds(m.decompose_ms, "%.0f ms"),
      "Splitting the takes into components (on the worker, not in the way of the editor)");
  const std::string synthesis = "Making the " + m.result + " from the components";
  row("Synthesis", milliseconds(m.synthesize_ms, "%.3f ms"), synthesis.c_str());
  const std::string cleanup = "Bone lengths and foot lock on the " + m.result;
  row("Clean-up", milliseconds(m.postprocess_ms, "%.3f ms"), cleanup.c_str());
  std::string all = m.result + ", all";
  all[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(all[0])));
  const std::string all_tip = "The whole " + m.result + " after a slider move, on the editor's thread";
  row(all.c_str(), milliseconds(m.result_ms, "%.3f ms"), all_tip.c_str());
  row("Export", milliseconds(times.export_ms), "The last export");
  row("Frame, CPU", milliseconds(times.frame_ms, "%.2f ms"), "Building one editor frame");
  row("Viewport, GPU", milliseconds(times.viewport_ms, "%.2f ms"), "Drawing the 3D view");
  ImGui::EndTable();
}

void MetricsPanel::draw_live_table() {
  if (live_ == nullptr || (live_->status().state == LiveState::kOff && live_->status().styled == 0)) return;
  const LiveMetrics& m = live_->metrics();
  ImGui::TextColored(kDimColor, "Live, over the last %.0f s", kLiveMetricsSeconds);
  if (!begin_table("##live")) return;
  char text[64];
  std::snprintf(text, sizeof text, "%.1f", m.frames_per_s);
  row("Styled frames/s", text, "Frames of the stream styled per second");
  auto microseconds = [&text](double us) {
    if (us < 0.0) return std::string("-");
    std::snprintf(text, sizeof text, "%.0f us", us);
    return std::string(text);
  };
  row("Latency, mean", microseconds(m.latency_mean_us),
      "From a frame's bytes read from the connection to the frame styled (microseconds)");
  row("Latency, 99th pct", microseconds(m.latency_p99_us), "99 of 100 frames are styled at least this soon");
  std::snprintf(text, sizeof text, "%lld", m.skipped);
  row("Dropped frames", text,
      "Lines of the stream that were not frames (a wrong number of values, not numbers, too long,\n"
      "another avatar's): skipped and counted");
  ImGui::EndTable();
  ImGui::Separator();
}

}  // namespace mostyle::ui
