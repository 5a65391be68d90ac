// The session dialog and message (ui/panels/session_dialog.h) as ImGui frames with no window: a
// confirmed path is returned, not acted on; a failure is said in the dialog, which stays open; a
// success closes it; the message shows an error until closed.
#include <catch2/catch.hpp>
#include <imgui.h>

#include "tests/ui/imgui_frame.h"
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
