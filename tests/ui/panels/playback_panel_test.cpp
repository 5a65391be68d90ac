// The timeline (ui/panels/playback_panel.h) over a loaded pair, as ImGui frames with no window,
// the mouse and the keys set by hand: K keys the style at the playhead, a key's mark is found on
// the slider, dragged in time (one undo step), clicked to go to it, right-clicked or Deleted away;
// the alpha slider shows the keyed value; the row of controls still fits 1280 pixels; hovering the
// slider tells where the output cycle under the mouse came from (a key's mark keeps its own tooltip).
#include <vector>

#include <catch2/catch.hpp>
#include <imgui_internal.h>  // ImGui::FindWindowByName, GImGui->HoveredId, ImHashData, ImHashStr

#include "tests/ui/imgui_frame.h"
#include "tests/ui/loaded_takes.h"
#include "ui/model/edit_history.h"
#include "ui/model/keyed_weights.h"
#include "ui/panels/layout.h"

using namespace mostyle;
using namespace mostyle::ui;
using test::LoadedTakes;

namespace {

constexpr int kDeleteKey = 4;  // io.KeyMap's slot for Delete in these tests

// The timeline and the undo history over a loaded pair, one editor frame at a time.
struct Timeline {
  LoadedTakes s;
  test::HeadlessImGui imgui;
  PlaybackPanel panel;
  EditHistory edits;

  Timeline() {
    ImGui::GetIO().KeyMap[ImGuiKey_Delete] = kDeleteKey;
    s.state.playback.playing = false;
  }
  // The panel, then the step recorded and the engine brought to the document, as the editor does.
  void frame() {
    imgui.begin_frame();
    s.engine.poll(s.state);
    panel.draw(s.state);
    edits.record(s.state, s.engine, ImGui::IsAnyItemActive());
    s.engine.sync(s.state, ImGui::IsAnyItemActive());
    imgui.end_frame();
  }
  const WeightKeys& keys() const { return s.state.document.controls.keys; }
  double fps() const { return s.state.reference_take()->rate(); }
  void go_to(int frame) { s.state.playback.time_s = (frame + 0.5) / fps(); }
  int playhead() const { return frame_at(*s.state.reference_take(), s.state.playback.time_s); }

  // Where key i's mark is: the mouse moved along the slider's top edge until ImGui gives it the
  // mark (its id: "##key" under PushID(i) in the playback window).
  ImVec2 find_mark(int i) {
    ImGuiIO& io = ImGui::GetIO();
    const PanelRect r = panel_rect(PanelId::kPlayback);
    const float y = r.y + ImGui::GetStyle().WindowPadding.y + 0.25f * ImGui::GetFrameHeight();
    for (float x = r.x; x < r.right(); x += 3.0f) {
      io.MousePos = ImVec2(x, y);
      frame();
      const ImGuiWindow* window = ImGui::FindWindowByName(panel_title(PanelId::kPlayback));
      const ImGuiID id = ImHashStr("##key", 0, ImHashData(&i, sizeof i, window->ID));
      if (GImGui->HoveredId == id) return io.MousePos;
    }
    FAIL("no mark for key " << i);
    return ImVec2();
  }
  // A click of mouse button `button` where the mouse is: pressed for a frame, then let go.
  void click(int button) {
    ImGuiIO& io = ImGui::GetIO();
    io.MouseDown[button] = true;
    frame();
    io.MouseDown[button] = false;
    frame();
  }
};

}  // namespace

TEST_CASE("timeline: K keys the style at the playhead, a mark drags in time as one undo step, and goes") {
  Timeline t;
  ImGuiIO& io = ImGui::GetIO();
  EditorState& state = t.s.state;
  t.go_to(10);
  t.frame();  // the starting state
  // K, at frame 10 with alpha 0.5: a key there, one undo step.
  io.AddInputCharacter('k');
  t.frame();
  REQUIRE(t.keys().size() == 1);
  CHECK(t.keys()[0].seconds == Approx(10 / t.fps()));
  CHECK(t.keys()[0].weights == std::vector<double>{0.5, 0.5});
  CHECK(t.edits.history().undo_steps() == 1);
  // At frame 40, alpha 1 from the alpha slider (held while it moves): auto-key adds a second key.
  t.go_to(40);
  t.frame();
  set_weights_at_playhead(state, 2, {0.0, 1.0});
  t.edits.record(state, t.s.engine, /*item_active=*/true);
  t.frame();
  REQUIRE(t.keys().size() == 2);
  CHECK(t.edits.history().undo_steps() == 2);
  CHECK(pair_alpha(state.document) == 0.5);

  // The second key's mark dragged 30 pixels left over a few frames: later than the first key
  // still, earlier than it was; one undo step when let go; the playhead stays.
  const ImVec2 at = t.find_mark(1);
  t.go_to(100);
  io.MousePos = at;
  io.MouseDown[0] = true;
  t.frame();
  for (int step = 1; step <= 6; ++step) {
    io.MousePos = ImVec2(at.x - 5.0f * step, at.y);
    t.frame();
  }
  io.MouseDown[0] = false;
  t.frame();
  REQUIRE(t.keys().size() == 2);
  const double moved = t.keys()[1].seconds;
  CHECK(moved < 40 / t.fps());
  CHECK(moved > t.keys()[0].seconds);
  CHECK(t.keys()[1].weights == std::vector<double>{0.0, 1.0});
  CHECK(t.edits.history().undo_steps() == 3);
  CHECK(t.playhead() == 100);
  // A click on a mark: the playhead goes to its key, where the alpha slider shows the key's alpha.
  io.MousePos = t.find_mark(1);
  t.click(0);
  CHECK(t.playhead() == static_cast<int>(std::lround(moved * t.fps())));
  CHECK(keyed_at_playhead(state, 2) == Keyed::kOnKey);
  CHECK(weights_at_playhead(state, 2)[1] == 1.0);
  CHECK(t.edits.history().undo_steps() == 3);  // going to a key edits nothing

  // A right-click removes the key under the mouse: one step.
  io.MousePos = t.find_mark(0);
  t.click(1);
  REQUIRE(t.keys().size() == 1);
  CHECK(t.keys()[0].seconds == moved);
  CHECK(t.edits.history().undo_steps() == 4);
  // Delete, with no mark under the mouse, removes the key at the playhead: the last one, which
  // leaves alpha at its value.
  io.MousePos = ImVec2(1.0f, 1.0f);
  io.KeysDown[kDeleteKey] = true;
  t.frame();
  io.KeysDown[kDeleteKey] = false;
  t.frame();
  CHECK(t.keys().empty());
  CHECK(pair_alpha(state.document) == 1.0);
  CHECK(t.edits.history().undo_steps() == 5);

  // Undone step by step: the last key back, then the first, then the drag.
  REQUIRE(t.edits.undo(state, t.s.engine));
  CHECK(t.keys().size() == 1);
  REQUIRE(t.edits.undo(state, t.s.engine));
  REQUIRE(t.keys().size() == 2);
  REQUIRE(t.edits.undo(state, t.s.engine));
  CHECK(t.keys()[1].seconds == Approx(40 / t.fps()));
}

TEST_CASE("timeline: with keys, the row of controls and marks is one row of a 1280 pixel window") {
  Timeline t;
  for (int frame : {0, 40, 80}) {
    t.go_to(frame);
    key_at_playhead(t.s.state, 2);
  }
  t.frame();
  t.frame();
  const ImGuiWindow* window = ImGui::FindWindowByName(panel_title(PanelId::kPlayback));
  REQUIRE(window != nullptr);
  CHECK(window->Size.x == Approx(1280.0f - 2.0f * kLayoutMargin));
  CHECK(window->ContentSize.y <= ImGui::GetFrameHeight() + 1.0f);  // the marks sit on the slider's row
  CHECK(window->ContentSize.x <= window->Size.x);
}

TEST_CASE("timeline: hovering the slider tells which cycle of each take the output cycle came from") {
  Timeline t;
  ImGuiIO& io = ImGui::GetIO();
  const std::vector<CycleProvenance>& spans = t.s.state.cycle_provenance;
  REQUIRE(spans.size() >= 2);
  // The tooltip is ImGui's window "##Tooltip_00", drawn this frame or not. (ImGui's log cannot read
  // its text: every window's End finishes a log; the words are provenance_text's, tested with the model.)
  auto tooltip_shown = [] {
    const ImGuiWindow* w = ImGui::FindWindowByName("##Tooltip_00");
    return w != nullptr && w->Active;
  };
  // The mouse along the slider's lower half (below the keys' marks), left to right: each output
  // cycle's span in turn under it, in order, with a tooltip, without moving the playhead.
  const PanelRect r = panel_rect(PanelId::kPlayback);
  const float y = r.y + ImGui::GetStyle().WindowPadding.y + 0.75f * ImGui::GetFrameHeight();
  std::vector<int> met;
  for (float x = r.x; x < r.right(); x += 2.0f) {
    io.MousePos = ImVec2(x, y);
    t.frame();
    const int span = t.panel.hovered_span();
    if (span < 0) continue;
    CHECK(tooltip_shown());
    if (met.empty() || met.back() != span) met.push_back(span);
  }
  CHECK(t.playhead() == 0);  // hovering moves nothing
  REQUIRE(met.size() == spans.size());  // every span, once, in order
  for (size_t i = 0; i < met.size(); ++i) CHECK(met[i] == static_cast<int>(i));
  // Away from the slider: no span, no tooltip.
  io.MousePos = ImVec2(r.x + 1.0f, r.y - 40.0f);
  t.frame();
  CHECK(t.panel.hovered_span() == -1);
  CHECK_FALSE(tooltip_shown());

  // Over a key's mark the key's tooltip wins: no span.
  key_at_playhead(t.s.state, 2);
  io.MousePos = t.find_mark(0);
  t.frame();
  CHECK(t.panel.hovered_span() == -1);
  CHECK(tooltip_shown());
  // Just below the mark, on the slider: the span of the key's frame.
  io.MousePos.y = y;
  t.frame();
  CHECK(t.panel.hovered_span() == provenance_at(spans, 0));
}
