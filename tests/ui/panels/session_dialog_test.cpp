// The session dialog and message (ui/panels/session_dialog.h) as ImGui frames with no window: a
// confirmed path is returned, not acted on; a failure is said in the dialog, which stays open; a
// success closes it; the message shows an error until closed.
#include <string>

#include <catch2/catch.hpp>
#include <imgui.h>
#include <imgui_internal.h>  // GImGui->Windows: the display order

#include "tests/ui/imgui_frame.h"
#include "ui/panels/fitted_text.h"
#include "ui/panels/session_dialog.h"

using namespace mostyle::ui;

TEST_CASE("session dialog: Enter returns the typed path; a failure stays in the dialog, a success closes it") {
  mostyle::test::HeadlessImGui imgui;
  ImGuiIO& io = ImGui::GetIO();
  io.KeyMap[ImGuiKey_Enter] = 1;
  SessionDialog dialog;
  SessionMessage message;
  auto frame = [&](bool enter) {
    io.KeysDown[1] = enter;
    imgui.begin_frame();
    const SessionDialog::Request r = dialog.draw({"/s/monday.mostyle"});
    if (!dialog.is_open()) message.draw(false);
    imgui.end_frame();
    return r;
  };
  CHECK(frame(false).kind == SessionDialog::Kind::kNone);  // closed: nothing drawn, nothing asked
  dialog.open(SessionDialog::Kind::kSave, "day1.mostyle");
  CHECK(dialog.is_open());
  for (int i = 0; i < 3; ++i) CHECK(frame(false).kind == SessionDialog::Kind::kNone);  // the field has focus
  SessionDialog::Request r = frame(true);
  CHECK(r.kind == SessionDialog::Kind::kSave);
  CHECK(r.path == "day1.mostyle");
  frame(false);
  // It could not be written: said in the dialog, which stays for the path to be corrected.
  dialog.failed("day1.mostyle: cannot write: no such folder");
  for (int i = 0; i < 2; ++i) frame(false);
  CHECK(dialog.is_open());
  // Written: the dialog closes and the message shows.
  dialog.done();
  message.set("Saved the session to /s/day1.mostyle", false);
  frame(false);
  CHECK_FALSE(dialog.is_open());
  imgui.begin_frame();
  message.draw(false);
  CHECK(imgui.end_frame() > 0);
  CHECK(message.text() == "Saved the session to /s/day1.mostyle");
  // An error stays until closed; screenshots hide successes only.
  message.set("bad.mostyle:3: unknown key", true);
  imgui.begin_frame();
  message.draw(/*hide_successes=*/true);
  CHECK(imgui.end_frame() > 0);
  message.set("Saved", false);
  imgui.begin_frame();
  message.draw(/*hide_successes=*/true);
  CHECK(imgui.end_frame() == 0);
}

TEST_CASE("session message: drawn over a panel that lies where it shows, even one focused after it") {
  mostyle::test::HeadlessImGui imgui(1280.0f, 720.0f);
  SessionMessage message;
  message.set("Opened the session /s/monday.mostyle", false);
  int session_at = -1, panel_at = -1;
  for (int frame = 0; frame < 4; ++frame) {
    imgui.begin_frame();
    // A panel over the bottom middle of the window (the style palette's place), focused each frame.
    ImGui::SetNextWindowPos(ImVec2(360.0f, 480.0f));
    ImGui::SetNextWindowSize(ImVec2(560.0f, 180.0f));
    ImGui::SetNextWindowFocus();
    ImGui::Begin("Style palette");
    ImGui::TextUnformatted("weights");
    ImGui::End();
    message.draw(false);
    imgui.end_frame();
  }
  const ImVector<ImGuiWindow*>& order = GImGui->Windows;  // back to front
  for (int i = 0; i < order.Size; ++i) {
    if (std::string(order[i]->Name) == "Session") session_at = i;
    if (std::string(order[i]->Name) == "Style palette") panel_at = i;
  }
  REQUIRE(session_at >= 0);
  REQUIRE(panel_at >= 0);
  CHECK(session_at > panel_at);
}

TEST_CASE("fitted text: whole when it fits, else cut with '...' within the width") {
  mostyle::test::HeadlessImGui imgui;
  imgui.begin_frame();
  const std::string name = "samba_dancing";
  const float whole = ImGui::CalcTextSize(name.c_str()).x;
  CHECK(fitted(name, whole) == name);
  const std::string cut = fitted(name, 0.6f * whole);
  CHECK(cut.size() > 3);
  CHECK(cut.substr(cut.size() - 3) == "...");
  CHECK(name.rfind(cut.substr(0, cut.size() - 3), 0) == 0);
  CHECK(ImGui::CalcTextSize(cut.c_str()).x <= 0.6f * whole);
  CHECK(fitted(name, 1.0f) == "...");
  imgui.end_frame();
}
