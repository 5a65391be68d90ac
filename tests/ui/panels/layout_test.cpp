// The editor's layout (ui/panels/layout.h) as a pure function and as the panels use it in ImGui frames
// with no window, the playback's end of take, lengths in words, and the files panel's names.
#include <imgui.h>
#include <imgui_internal.h>  // ImGui::FindWindowByName: where the panels really are

#include <cstring>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "tests/ui/imgui_frame.h"
#include "tests/ui/loaded_takes.h"
#include "ui/panels/layout.h"

using namespace mostyle;
using namespace mostyle::ui;

namespace {

constexpr float kPixel = 1.5f;  // ImGui floors window positions and sizes to whole pixels (after float round-off)

struct Display {
  float width, height;
};
const std::vector<Display> kDisplays = {{1280.0f, 720.0f}, {1920.0f, 1080.0f}, {2560.0f, 1440.0f}};

PanelRect window_rect(PanelId id) {
  const ImGuiWindow* w = ImGui::FindWindowByName(panel_title(id));
  REQUIRE(w != nullptr);
  return PanelRect{w->Pos.x, w->Pos.y, w->Size.x, w->Size.y};
}

// One editor frame of the panels, laid out as app/editor/editor.cpp does.
void panels_frame(test::HeadlessImGui& imgui, test::LoadedTakes& s, std::vector<std::unique_ptr<Panel>>& panels,
                  glm::vec2* last_display) {
  imgui.begin_frame();
  track_display_size(s.state, last_display);
  s.engine.poll(s.state);
  for (auto& panel : panels) panel->draw(s.state);
  s.state.view.reset_layout = false;
  s.engine.sync(s.state);
  imgui.end_frame();
}

}  // namespace

TEST_CASE("the layout keeps every panel inside the display, off the centre and off each other") {
  for (const Display& d : kDisplays) {
    CAPTURE(d.width, d.height);
    const auto rects = compute_layout(d.width, d.height);
    const PanelRect centre = clear_centre(d.width, d.height);
    CHECK(centre.x == Approx(0.35f * d.width));
    CHECK(centre.bottom() == Approx(0.65f * d.height));
    for (int i = 0; i < kPanelCount; ++i) {
      CAPTURE(panel_title(static_cast<PanelId>(i)));
      const PanelRect& r = rects[static_cast<size_t>(i)];
      CHECK(r.w > 100.0f);
      CHECK(r.h >= kPlaybackBarHeight);
      CHECK(r.inside(d.width, d.height));
      CHECK_FALSE(r.overlaps(centre));
      for (int j = i + 1; j < kPanelCount; ++j) CHECK_FALSE(r.overlaps(rects[static_cast<size_t>(j)]));
    }
    // Side columns of about a quarter of the width, 340 to 420 px; the bar spans the window.
    const PanelRect& left = rects[static_cast<size_t>(PanelId::kParameters)];
    const PanelRect& right = rects[static_cast<size_t>(PanelId::kMetrics)];
    CHECK(left.w >= kSideMin);
    CHECK(left.w <= kSideMax);
    CHECK(right.w == left.w);
    CHECK(rects[static_cast<size_t>(PanelId::kPlayback)].w == Approx(d.width - 2.0f * kLayoutMargin));
  }
  // Smaller windows: the columns narrow rather than cover the centre.
  for (const Display& d : std::vector<Display>{{640.0f, 360.0f}, {800.0f, 600.0f}, {1024.0f, 768.0f}}) {
    CAPTURE(d.width, d.height);
    const auto rects = compute_layout(d.width, d.height);
    for (const PanelRect& r : rects) {
      CHECK(r.inside(d.width, d.height));
      CHECK_FALSE(r.overlaps(clear_centre(d.width, d.height)));
    }
  }
}

TEST_CASE("the panels take their places from the layout at 1280x720, 1920x1080 and 2560x1440") {
  test::LoadedTakes s;
  test::HeadlessImGui imgui;
  auto panels = test::all_panels(s.engine);
  glm::vec2 last_display(0.0f);
  for (const Display& d : kDisplays) {
    CAPTURE(d.width, d.height);
    ImGui::GetIO().DisplaySize = ImVec2(d.width, d.height);
    for (int frame = 0; frame < 3; ++frame) panels_frame(imgui, s, panels, &last_display);
    const auto want = compute_layout(d.width, d.height, playback_bar_height());
    const PanelRect centre = clear_centre(d.width, d.height);
    for (int i = 0; i < kPanelCount; ++i) {
      const PanelId id = static_cast<PanelId>(i);
      CAPTURE(panel_title(id));
      const PanelRect r = window_rect(id);
      CHECK(r.inside(d.width, d.height));
      CHECK_FALSE(r.overlaps(centre));
      const PanelRect& w = want[static_cast<size_t>(i)];
      CHECK(r.x == Approx(w.x).margin(kPixel));
      CHECK(r.y == Approx(w.y).margin(kPixel));
      CHECK(r.w == Approx(w.w).margin(kPixel));
      CHECK(r.h == Approx(w.h).margin(kPixel));
    }
  }
}

TEST_CASE("a moved panel stays until Reset layout or a new display size") {
  test::LoadedTakes s;
  test::HeadlessImGui imgui;
  auto panels = test::all_panels(s.engine);
  glm::vec2 last_display(0.0f);
  ImGui::GetIO().DisplaySize = ImVec2(1280.0f, 720.0f);
  for (int frame = 0; frame < 2; ++frame) panels_frame(imgui, s, panels, &last_display);
  const PanelRect placed = window_rect(PanelId::kFiles);

  ImGui::SetWindowPos(panel_title(PanelId::kFiles), ImVec2(500.0f, 300.0f));  // the animator drags it
  for (int frame = 0; frame < 2; ++frame) panels_frame(imgui, s, panels, &last_display);
  CHECK(window_rect(PanelId::kFiles).x == 500.0f);
  CHECK(window_rect(PanelId::kFiles).y == 300.0f);

  command_reset_layout(s.state);
  panels_frame(imgui, s, panels, &last_display);
  CHECK(window_rect(PanelId::kFiles).x == Approx(placed.x).margin(kPixel));
  CHECK(window_rect(PanelId::kFiles).y == Approx(placed.y).margin(kPixel));
  CHECK_FALSE(s.state.view.reset_layout);

  ImGui::SetWindowPos(panel_title(PanelId::kFiles), ImVec2(500.0f, 300.0f));
  ImGui::GetIO().DisplaySize = ImVec2(1600.0f, 900.0f);  // the window is resized
  panels_frame(imgui, s, panels, &last_display);
  const PanelRect want = compute_layout(1600.0f, 900.0f, playback_bar_height())[static_cast<size_t>(PanelId::kFiles)];
  CHECK(window_rect(PanelId::kFiles).x == Approx(want.x).margin(kPixel));
  CHECK(window_rect(PanelId::kFiles).y == Approx(want.y).margin(kPixel));
}

TEST_CASE("with loop off, playback stops on the last frame and Play starts it again from the first") {
  Playback p;
  p.loop = false;
  p.playing = true;
  const double length = 2.0;
  advance_playback(p, 1.5, length);
  CHECK(p.playing);
  CHECK(p.time_s == 1.5);
  advance_playback(p, 1.0, length);
  CHECK_FALSE(p.playing);  // the button reads Play
  CHECK(p.time_s == length);
  advance_playback(p, 1.0, length);  // paused: stays
  CHECK(p.time_s == length);
  toggle_playback(p, length);
  CHECK(p.playing);
  CHECK(p.time_s == 0.0);
  // Loop on: back to the start, still playing.
  p.loop = true;
  p.time_s = 1.9;
  advance_playback(p, 0.5, length);
  CHECK(p.playing);
  CHECK(p.time_s == 0.0);
  // Paused in the middle: Play goes on from there.
  p.playing = false;
  p.time_s = 0.7;
  toggle_playback(p, length);
  CHECK(p.playing);
  CHECK(p.time_s == 0.7);
}

TEST_CASE("the files panel names files without their folders") {
  PathField f;
  f.set("/data/mocap/walk.bvh");
  CHECK(std::string(f.text) == "walk.bvh");
  CHECK(f.folder == "/data/mocap");
  CHECK(f.path() == "/data/mocap/walk.bvh");
  std::strcpy(f.text, "run.bvh");  // a name typed: in the same folder
  CHECK(f.path() == "/data/mocap/run.bvh");
  std::strcpy(f.text, "other/run.bvh");  // a path typed: as it is
  CHECK(f.path() == "other/run.bvh");
  f.set("walk.bvh");
  CHECK(f.folder.empty());
  CHECK(f.path() == "walk.bvh");
  f.set("");
  CHECK(f.path().empty());

  CHECK(without_folders("/data/mocap/walk.bvh:42: expected CHANNELS", {"/data", "/data/mocap"}) ==
        "walk.bvh:42: expected CHANNELS");
  CHECK(without_folders("Exported to /tmp/out/blend.bvh (120 frames)", {"/tmp/out/"}) ==
        "Exported to blend.bvh (120 frames)");
  CHECK(without_folders("a/b.bvh", {"", ".", "/"}) == "a/b.bvh");
}
