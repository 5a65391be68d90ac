// The takes' layers (ui/panels/layers_panel.h), one view for any number of takes, as ImGui frames
// with no window, the mouse moved and clicked by hand: two takes and four, each a row with its
// weight and its timeline, the weights kept summing to 1, a take's alignment in its own tab; a
// pair's transfer (B's style on A) as `transfer A --style B` makes it; a palette's transfer with a
// neutral take or none (the content its own neutral); Transfer and Mix each on their own timing.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <imgui_internal.h>  // ImGui::FindWindowByName, GImGui->HoveredId, ImHashData, ImHashStr

#include "tests/test_data.h"
#include "tests/ui/imgui_frame.h"
#include "tests/ui/loaded_takes.h"
#include "ui/model/document_mix.h"
#include "ui/model/keyed_weights.h"
#include "ui/model/result_view.h"
#include "ui/model/take_structure.h"
#include "ui/panels/layers_panel.h"
#include "ui/panels/layout.h"

using namespace mostyle;
using namespace mostyle::ui;
using test::LoadedTakes;

namespace {

const char* const kTitle = panel_title(PanelId::kLayers);
constexpr const char* kNone = "none: the content is its own neutral";

std::vector<std::string> bundled(int takes) {
  const char* names[] = {"cmu142_walk_happy.bvh", "cmu142_walk_marching.bvh", "cmu142_walk_joy.bvh",
                         "cmu142_walk_clumsy.bvh"};
  std::vector<std::string> out;
  for (int i = 0; i < takes; ++i) out.push_back(test::asset(std::string("motions/") + names[i]));
  return out;
}

using IdIn = ImGuiID (*)(const ImGuiWindow*, const void*);

// An item labelled `text` in the window given.
ImGuiID labelled(const ImGuiWindow* w, const void* text) { return ImHashStr(static_cast<const char*>(text), 0, w->ID); }

// The Alignment tab (its label's id "###alignment" in the "##layers" tab bar).
ImGuiID alignment_tab(const ImGuiWindow* w, const void*) { return ImHashStr("###alignment", 0, ImHashStr("##layers", 0, w->ID)); }

// Take `take`'s control `label` in a take's row (under PushID(take) in the rows' child window).
struct RowItem {
  int take;
  const char* label;
};
ImGuiID row_item(const ImGuiWindow*, const void* arg) {
  const RowItem& item = *static_cast<const RowItem*>(arg);
  const ImGuiWindow* w = GImGui->HoveredWindow;
  return w == nullptr ? ImGuiID(0) : ImHashStr(item.label, 0, ImHashData(&item.take, sizeof item.take, w->ID));
}

// The layers panel over `takes` bundled takes (k 6, sparsity 0.2), one editor frame at a time.
struct Layers {
  LoadedTakes s;
  test::HeadlessImGui imgui;
  LayersPanel panel{s.engine};

  explicit Layers(int takes = 3) {
    if (takes != 2) {
      s.engine.load_files(bundled(takes));
      s.engine.wait_idle(s.state);
    }
    s.state.playback.playing = false;
  }
  // A frame as the editor draws it: the panel, then the engine brought to the document.
  int frame() {
    imgui.begin_frame();
    s.engine.poll(s.state);
    panel.draw(s.state);
    s.engine.sync(s.state, ImGui::IsAnyItemActive());
    return imgui.end_frame();
  }
  // The mouse moved over window `title` until ImGui gives the item `id` the hover; false when
  // no point of the window does.
  bool hover(const char* title, IdIn id_in, const void* arg) {
    ImGuiIO& io = ImGui::GetIO();
    frame();  // a window just opened (a combo's list) takes its size in its first frames
    frame();
    const ImGuiWindow* window = ImGui::FindWindowByName(title);
    if (window == nullptr) return false;
    const ImRect r = window->Rect();
    for (float y = r.Min.y + 2.0f; y < r.Max.y; y += 4.0f)
      for (float x = r.Min.x + 2.0f; x < r.Max.x; x += 8.0f) {
        io.MousePos = ImVec2(x, y);
        frame();
        window = ImGui::FindWindowByName(title);
        if (window != nullptr && GImGui->HoveredId == id_in(window, arg)) return true;
      }
    return false;
  }
  void click() {
    ImGuiIO& io = ImGui::GetIO();
    io.MouseDown[0] = true;
    frame();
    io.MouseDown[0] = false;
    frame();
  }
  bool has(int take, const char* label) {
    const RowItem item{take, label};
    return hover(kTitle, row_item, &item);
  }
  // Opens the Neutral combo and picks the entry labelled `label`.
  void choose_neutral(const std::string& label) {
    REQUIRE(hover(kTitle, labelled, "Neutral"));
    click();
    // A combo's list is a popup window of its own, named by its depth in the popup stack.
    REQUIRE(hover("##Combo_00", labelled, label.c_str()));
    click();
  }
  std::vector<double> mix_weights() {
    const int n = s.engine.takes()->size();
    return take_weights(mix_params_for(s.state.document, *s.engine.snapshot().decomposed, n).layers, n);
  }
  // Take `take`'s weight field dragged `pixels` to the left from its middle, a few pixels a frame.
  void drag_weight(int take, float pixels) {
    const RowItem item{take, "##w"};
    REQUIRE(hover(kTitle, row_item, &item));
    ImGuiIO& io = ImGui::GetIO();
    const ImVec2 at = io.MousePos;
    io.MouseDown[0] = true;
    frame();
    for (float moved = 2.0f; moved <= pixels; moved += 2.0f) {
      io.MousePos = ImVec2(at.x - moved, at.y);
      frame();
    }
    io.MouseDown[0] = false;
    frame();
  }
};

// The largest horizontal distance between two takes' hips over their frames (Y up).
double hips_gap(const ShownMotion& a, const ShownMotion& b) {
  double gap = 0.0;
  for (int f = 0; f < std::min(a.frames(), b.frames()); ++f) {
    const Eigen::Vector3d d = a.positions.row(f).head<3>() - b.positions.row(f).head<3>();
    gap = std::max(gap, std::hypot(d.x(), d.z()));
  }
  return gap;
}

// The mean distance of the joints from where they stand on the hips, between two takes at a frame.
double pose_distance(const ShownMotion& a, const ShownMotion& b, int frame) {
  const int joints = static_cast<int>(a.positions.cols() / 3);
  double sum = 0.0;
  for (int j = 0; j < joints; ++j) {
    const Eigen::Vector3d pa = a.positions.row(frame).segment<3>(3 * j) - a.positions.row(frame).head<3>();
    const Eigen::Vector3d pb = b.positions.row(frame).segment<3>(3 * j) - b.positions.row(frame).head<3>();
    sum += (pa - pb).norm();
  }
  return sum / joints;
}

}  // namespace

TEST_CASE("layers panel: two takes, a row each, B's weight moves A's, and B's alignment in its tab") {
  Layers t(2);
  REQUIRE(t.s.engine.takes()->size() == 2);
  t.frame();
  CHECK(t.has(0, "##w"));
  CHECK(t.has(1, "##w"));
  CHECK_FALSE(t.has(2, "##w"));
  CHECK(t.has(0, "##timeline"));
  CHECK(t.has(1, "##timeline"));
  // B's weight dragged down: A's follows (they sum to 1), the result is mixed at once.
  const Eigen::MatrixXd before = t.s.engine.result()->motion.world;
  t.drag_weight(1, 30.0f);
  const std::vector<double> w = layer_weights(t.s.state.document);
  REQUIRE(w.size() == 2);
  CHECK(w[1] < 0.5);
  CHECK(w[0] + w[1] == Approx(1.0));
  CHECK(pair_alpha(t.s.state.document) == w[1]);
  // Another result: its length too where the weights play another count of B's extra cycles.
  const Eigen::MatrixXd& after = t.s.engine.result()->motion.world;
  CHECK((after.rows() != before.rows() || !after.isApprox(before)));
  // The alignment of B onto A: its tab draws the plots.
  CHECK(t.panel.aligned_take() == 1);
  REQUIRE(t.hover(kTitle, alignment_tab, nullptr));
  t.click();
  CHECK(t.frame() > 1000);
  const ImGuiWindow* window = ImGui::FindWindowByName(kTitle);
  REQUIRE(window != nullptr);
  CHECK(window->DrawList->VtxBuffer.Size > 2000);  // the cost matrix's cells and the curves
}

TEST_CASE("layers panel: four takes, a row each, weights that sum to 1, and the alignment of the take picked") {
  Layers t(4);
  REQUIRE(t.s.engine.takes()->size() == 4);
  t.frame();
  for (int i = 0; i < 4; ++i) {
    INFO("take " << i);
    CHECK(t.has(i, "##w"));
    CHECK(t.has(i, "##timeline"));
  }
  t.drag_weight(2, 20.0f);
  const std::vector<double> w = layer_weights(t.s.state.document);
  REQUIRE(w.size() == 4);
  CHECK(w[2] < 0.25);
  double sum = 0.0;
  for (double x : w) sum += x;
  CHECK(sum == Approx(1.0));
  CHECK(t.s.engine.result_view().error().empty());
  // The last take's name picks its alignment, which the tab then shows.
  const RowItem name{3, "###name"};
  REQUIRE(t.hover(kTitle, row_item, &name));
  t.click();
  CHECK(t.panel.aligned_take() == 3);
  REQUIRE(t.hover(kTitle, alignment_tab, nullptr));
  t.click();
  CHECK(t.frame() > 1000);
  // Each take's row tells its structure: the bundled walks are gait cycles.
  const PreparedTake& take = t.s.engine.takes()->takes[3];
  REQUIRE_FALSE(take.cycles.cycles.empty());
  CHECK_THAT(frame_structure_words(take, take.cycles.cycles.front().begin), Catch::StartsWith("gait cycle 1 of"));
}

TEST_CASE("layers panel: a pair's transfer puts B's style on A, which keeps its path, as `transfer A --style B` does") {
  Layers t(2);
  LoadedTakes& s = t.s;
  s.state.document.overlay = true;  // no lateral offsets: the takes can be compared
  DocumentControls& c = s.state.document.controls;
  c.timing_a = true;
  set_pair_alpha(s.state.document, 1.0);
  s.engine.sync(s.state);
  const ShownMotion& a = s.state.shown[0];
  const ShownMotion& result = s.state.shown[result_index(2)];
  const Eigen::VectorXd ys = a.positions.row(0)(Eigen::seqN(1, a.positions.cols() / 3, 3)).transpose();
  const double height = ys.maxCoeff() - ys.minCoeff();
  // A blend at alpha 1 walks B's route: the marching take goes its own way, far from A's.
  CHECK(hips_gap(result, a) > height);
  CHECK(result.label.rfind("blend", 0) == 0);

  // Transfer clicked: A's timeline, A its own neutral (no Neutral choice for two takes), the
  // transfer shown; B's strength in its row, A the content.
  c.timing_a = false;
  REQUIRE(t.hover(kTitle, labelled, "Transfer"));
  t.click();
  CHECK(c.transfer);
  CHECK(c.timing_a);
  CHECK(transfer_neutral(c, 2) == 0);
  CHECK_FALSE(t.hover(kTitle, labelled, "Neutral"));
  CHECK(t.has(1, "##strength"));
  CHECK_FALSE(t.has(0, "##strength"));
  REQUIRE(s.engine.result() != nullptr);
  const MixParams m = mix_params_for(s.state.document, *s.engine.snapshot().decomposed, 2);
  CHECK(m.feet_of_reference);
  CHECK(m.path_leash == transfer_path_leash(TransferNeutral::kContent, false));
  CHECK(take_weights(m.layers, 2) == std::vector<double>{0.0, 1.0});
  REQUIRE(m.layers.additive.size() == 1);  // B added to A, from A
  CHECK(m.layers.additive[0].take == 1);
  CHECK(m.layers.additive[0].from == 0);
  // A's whole take, its hips within the leash (a fifth of the body's height) of A's own.
  CHECK(result.frames() == a.frames());
  CHECK(hips_gap(result, a) < 0.25 * height);
  CHECK(result.label == "transfer  strength 1.00");
  // B's style: where it stands on its hips, the body is not A's.
  CHECK(pose_distance(result, a, a.frames() / 2) > 0.02 * height);
  // Mix clicked: a blend again, on the timing the blend had, at the alpha the strength was.
  REQUIRE(t.hover(kTitle, labelled, "Mix"));
  t.click();
  CHECK_FALSE(c.transfer);
  CHECK_FALSE(c.timing_a);
  CHECK(pair_alpha(s.state.document) == 1.0);
  CHECK(result.label.rfind("blend", 0) == 0);
}

TEST_CASE("layers panel: a transfer's neutral can be none, the content its own neutral") {
  Layers t;
  DocumentControls& c = t.s.state.document.controls;
  c.transfer = true;
  t.frame();
  REQUIRE(t.s.engine.takes()->size() == 3);
  // No take is named neutral: the transfer starts with the content its own neutral.
  CHECK(c.content_neutral);
  c.content_neutral = false;
  set_layer_weights(t.s.state.document, {1.0, 0.25, 0.5});
  t.frame();
  // A neutral take (marching): joy is the only style.
  REQUIRE(transfer_neutral(c, 3) == 1);
  CHECK(t.mix_weights() == std::vector<double>{1.0, -0.5, 0.5});
  CHECK_FALSE(t.has(1, "##strength"));
  CHECK(t.has(2, "##strength"));

  t.choose_neutral(kNone);
  CHECK(c.content_neutral);
  CHECK(transfer_neutral(c, 3) == 0);
  // Both other takes are styles: content + 0.25 (marching - content) + 0.5 (joy - content).
  CHECK(t.mix_weights() == std::vector<double>{0.25, 0.25, 0.5});
  CHECK(t.has(1, "##strength"));
  CHECK(t.has(2, "##strength"));
  // The mix the editor shows is made with them, without an error.
  CHECK(t.s.engine.result_view().error().empty());
  REQUIRE(t.s.engine.result_view().mix() != nullptr);

  // A take chosen again is the neutral again.
  t.choose_neutral("marching");
  CHECK_FALSE(c.content_neutral);
  CHECK(c.neutral == 1);
  CHECK(t.mix_weights() == std::vector<double>{1.0, -0.5, 0.5});
}

TEST_CASE("layers panel: Transfer comes in on the content's timing, as the command line's, and Mix on mixed timing") {
  Layers t;
  bool& timing = t.s.state.document.controls.timing_a;
  DocumentControls& c = t.s.state.document.controls;
  c.transfer = false;
  timing = false;
  t.frame();
  REQUIRE(t.hover(kTitle, labelled, "Transfer"));
  t.click();
  CHECK(c.transfer);
  CHECK(timing);
  CHECK(mix_params_for(t.s.state.document, *t.s.engine.snapshot().decomposed, 3).reference_timing);
  // Clicked again, it changes nothing (a timing the animator set stays).
  timing = false;
  t.click();
  CHECK(c.transfer);
  CHECK_FALSE(timing);
  REQUIRE(t.hover(kTitle, labelled, "Mix"));
  timing = true;
  t.click();
  CHECK_FALSE(c.transfer);
  CHECK_FALSE(timing);
}

TEST_CASE("layers panel: a weight's field shows its sign whole, and a 46 pixel drag moves it by less than 0.5") {
  Layers t;
  set_layer_weights(t.s.state.document, {1.3, -0.15, -0.15});
  t.frame();
  const RowItem field{0, "##w"};
  REQUIRE(t.hover(kTitle, row_item, &field));
  ImGuiIO& io = ImGui::GetIO();
  const ImVec2 found = io.MousePos;
  const ImGuiID id = GImGui->HoveredId;
  // Its width: how far the hover reaches on either side along that row.
  float left = found.x, right = found.x;
  for (float x = found.x; x > found.x - 400.0f; x -= 1.0f) {
    io.MousePos = ImVec2(x, found.y);
    t.frame();
    if (GImGui->HoveredId != id) break;
    left = x;
  }
  for (float x = found.x; x < found.x + 400.0f; x += 1.0f) {
    io.MousePos = ImVec2(x, found.y);
    t.frame();
    if (GImGui->HoveredId != id) break;
    right = x;
  }
  const float needed = ImGui::CalcTextSize("-0.50").x + 2.0f * ImGui::GetStyle().FramePadding.x;
  CHECK(right - left + 1.0f >= needed + ImGui::GetFontSize());  // the value, its sign, and room to spare
  // A 46 pixel drag to the left from the middle.
  const float middle = 0.5f * (left + right);
  io.MousePos = ImVec2(middle, found.y);
  t.frame();
  io.MouseDown[0] = true;
  t.frame();
  for (int step = 1; step <= 23; ++step) {
    io.MousePos = ImVec2(middle - 2.0f * static_cast<float>(step), found.y);
    t.frame();
  }
  io.MouseDown[0] = false;
  t.frame();
  const double after = t.s.state.document.layers[0].weight;
  CAPTURE(after);
  CHECK(after < 1.3 - 0.05);  // it moved
  CHECK(after > 1.3 - 0.5);   // finely
}

TEST_CASE("layers panel: the pad's weights sum to 1, a vertex is its take alone") {
  for (int n : {2, 3, 5}) {
    INFO(n << " takes");
    for (int i = 0; i < n; ++i) {
      const std::vector<double> w = pad_weights(pad_vertex(i, n), n);
      CHECK(w[static_cast<size_t>(i)] == 1.0);
      CHECK(pad_point(w).x == Approx(pad_vertex(i, n).x).margin(1e-6));
    }
    const std::vector<double> centre = pad_weights(glm::vec2(0.1f, 0.2f), n);
    double sum = 0.0;
    for (double w : centre) sum += w;
    CHECK(sum == Approx(1.0));
  }
  // Setting a weight keeps the sum and the mix's range.
  const std::vector<double> w = set_weight_keeping_sum({0.25, 0.25, 0.5}, 2, 1.4);
  CHECK(w[2] == Approx(1.4));
  CHECK(w[0] + w[1] + w[2] == Approx(1.0));
  CHECK(set_weight_keeping_sum({0.5, 0.5}, 0, 2.0)[0] == Approx(1.5));  // clamped to the mix's range
}
