// The style palette panel (ui/panels/palette_panel.h) in transfer mode over a palette of three
// bundled takes, as ImGui frames with no window, the mouse moved and clicked by hand: the Neutral
// choice offers "none" (the content is its own neutral), which makes every other take a style
// with a strength slider and the content's weight 1 minus the strengths; choosing a take again
// brings its neutral back.
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <imgui_internal.h>  // ImGui::FindWindowByName, GImGui->HoveredId, ImHashData, ImHashStr

#include "tests/test_data.h"
#include "tests/ui/imgui_frame.h"
#include "tests/ui/loaded_session.h"
#include "ui/model/keyed_weights.h"
#include "ui/model/document_mix.h"
#include "ui/model/result_view.h"
#include "ui/panels/palette_panel.h"

using namespace mostyle;
using namespace mostyle::ui;
using test::LoadedSession;

namespace {

constexpr const char* kTitle = "Style palette";
constexpr const char* kNone = "none: the content is its own neutral";

// The palette panel over happy (the content), marching and joy, one editor frame at a time.
struct Palette {
  LoadedSession s;
  test::HeadlessImGui imgui;
  PalettePanel panel{s.session};

  Palette() {
    s.session.load_files({test::asset("motions/cmu142_walk_happy.bvh"),
                          test::asset("motions/cmu142_walk_marching.bvh"),
                          test::asset("motions/cmu142_walk_joy.bvh")});
    s.session.wait_idle(s.state);
    s.state.playback.playing = false;
    s.state.document.controls.palette.transfer = true;
  }
  void frame() {
    imgui.begin_frame();
    s.session.poll(s.state);
    panel.draw(s.state);
    s.session.sync(s.state);
    imgui.end_frame();
  }
  // The mouse moved over window `title` until ImGui gives the item `id` the hover; false when
  // no point of the window does.
  bool hover(const char* title, ImGuiID (*id_in)(const ImGuiWindow*, const void*), const void* arg) {
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
  // Opens the Neutral combo and picks the entry labelled `label`.
  void choose_neutral(const std::string& label) {
    auto labelled = [](const ImGuiWindow* w, const void* text) {
      return ImHashStr(static_cast<const char*>(text), 0, w->ID);
    };
    REQUIRE(hover(kTitle, labelled, "Neutral"));
    click();
    // A combo's list is a popup window of its own, named by its depth in the popup stack.
    REQUIRE(hover("##Combo_00", labelled, label.c_str()));
    click();
  }
  // Whether take i has a strength slider (its "##strength" under PushID(i)).
  bool has_strength(int i) {
    auto slider = [](const ImGuiWindow* w, const void* take) {
      return ImHashStr("##strength", 0, ImHashData(take, sizeof(int), w->ID));
    };
    return hover(kTitle, slider, &i);
  }
  std::vector<double> mix_weights() {
    return take_weights(mix_params_for(s.state.document, *s.session.snapshot().decomposed, 3).layers, 3);
  }
};

}  // namespace

TEST_CASE("palette panel: a transfer's neutral can be none, the content its own neutral") {
  Palette t;
  t.frame();
  REQUIRE(t.s.session.palette() != nullptr);
  PaletteControls& c = t.s.state.document.controls.palette;
  // No take is named neutral: the transfer starts with the content its own neutral.
  CHECK(c.content_neutral);
  c.content_neutral = false;
  c.strengths = {1.0, 0.25, 0.5};
  t.frame();
  // A neutral take (marching): joy is the only style.
  REQUIRE(transfer_neutral(c, 3) == 1);
  CHECK(t.mix_weights() == std::vector<double>{1.0, -0.5, 0.5});
  CHECK_FALSE(t.has_strength(1));
  CHECK(t.has_strength(2));

  t.choose_neutral(kNone);
  CHECK(c.content_neutral);
  CHECK(transfer_neutral(c, 3) == 0);
  // Both other takes are styles: content + 0.25 (marching - content) + 0.5 (joy - content).
  CHECK(t.mix_weights() == std::vector<double>{0.25, 0.25, 0.5});
  CHECK(t.has_strength(1));
  CHECK(t.has_strength(2));
  // The mix the editor shows is made with them, without an error.
  CHECK(t.s.session.result_view().error().empty());
  REQUIRE(t.s.session.result_view().mix() != nullptr);

  // A take chosen again is the neutral again.
  t.choose_neutral("marching");
  CHECK_FALSE(c.content_neutral);
  CHECK(c.neutral == 1);
  CHECK(t.mix_weights() == std::vector<double>{1.0, -0.5, 0.5});
}

TEST_CASE("palette panel: Transfer comes in on the content's timing, as the command line's, and Mix on mixed timing") {
  Palette t;
  bool& timing = t.s.state.document.controls.timing_a;
  PaletteControls& c = t.s.state.document.controls.palette;
  c.transfer = false;
  timing = false;
  t.frame();
  auto labelled = [](const ImGuiWindow* w, const void* text) { return ImHashStr(static_cast<const char*>(text), 0, w->ID); };
  REQUIRE(t.hover(kTitle, labelled, "Transfer"));
  t.click();
  CHECK(c.transfer);
  CHECK(timing);
  CHECK(mix_params_for(t.s.state.document, *t.s.session.snapshot().decomposed, 3).reference_timing);
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

TEST_CASE("palette panel: a weight's field shows its sign whole, and a 46 pixel drag moves it by less than 0.5") {
  Palette t;
  t.s.state.document.controls.palette.transfer = false;
  t.s.state.document.weights = {1.3, -0.15, -0.15};
  t.frame();
  REQUIRE(t.s.session.palette() != nullptr);
  // Take 0's weight field ("##w" under PushID(0) in the weights' child window).
  auto weight_field = [](const ImGuiWindow*, const void*) {
    const int take = 0;
    const ImGuiWindow* w = GImGui->HoveredWindow;
    return w == nullptr ? ImGuiID(0) : ImHashStr("##w", 0, ImHashData(&take, sizeof take, w->ID));
  };
  REQUIRE(t.hover(kTitle, weight_field, nullptr));
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
  const double after = t.s.state.document.weights[0];
  CAPTURE(after);
  CHECK(after < 1.3 - 0.05);  // it moved
  CHECK(after > 1.3 - 0.5);   // finely
}
