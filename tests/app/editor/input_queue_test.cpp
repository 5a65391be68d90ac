// Keys handed to ImGui at the pace of frames (app/editor/input_queue.h): no press lost at rest,
// and what is typed after a shortcut lands in the field the shortcut opens.
#include "app/editor/input_queue.h"

#include <cctype>
#include <cfloat>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include <catch2/catch.hpp>
#include <imgui.h>
#include <imgui_internal.h>  // ImGui::FindWindowByName, GImGui->HoveredId, ImHashData, ImHashStr

#include "tests/app/editor/offscreen_editor.h"
#include "tests/test_data.h"
#include "ui/panels/layout.h"

using namespace mostyle::app;
namespace fs = std::filesystem;

namespace {

constexpr int kRight = 262, kEnter = 257, kEscape = 256, kLeftControl = 341;

KeyEvent key(int k, int action, int mods = 0) { return {KeyEvent::Kind::kKey, k, 0, action, mods, 0}; }
KeyEvent character(unsigned c) { return {KeyEvent::Kind::kChar, 0, 0, 0, 0, c}; }

// What each frame takes, as "P262 R262 C100 | ..." (press, release, character).
std::string frames_of(InputQueue& q) {
  std::string text;
  while (!q.empty()) {
    if (!text.empty()) text += " |";
    for (const KeyEvent& e : q.take_frame()) {
      if (e.kind == KeyEvent::Kind::kChar) text += " C" + std::to_string(e.codepoint);
      else text += std::string(e.action == kActionRelease ? " R" : " P") + std::to_string(e.key);
    }
  }
  return text;
}

// One frame's events given to ImGui as the GLFW back-end's callbacks give them (imgui_impl_glfw
// 1.86).
void give_frame(InputQueue& queue, ImGuiIO& io) {
  for (const KeyEvent& ev : queue.take_frame(io.WantTextInput)) {
    if (ev.kind == KeyEvent::Kind::kChar) {
      io.AddInputCharacter(ev.codepoint);
      continue;
    }
    if (ev.action == kActionPress) io.KeysDown[ev.key] = true;
    if (ev.action == kActionRelease) io.KeysDown[ev.key] = false;
    io.KeyCtrl = io.KeysDown[kLeftControl];
  }
}

}  // namespace

TEST_CASE("input queue: one press a frame, no key changing twice, only releases after a shortcut") {
  InputQueue q;
  for (int i = 0; i < 3; ++i) {  // three taps between two frames
    q.push(key(kRight, kActionPress));
    q.push(key(kRight, kActionRelease));
  }
  CHECK(frames_of(q) == " P262 | R262 | P262 | R262 | P262 | R262");  // a key changes once a frame
  // Ctrl+S then "ab": the letters wait for the frame after the one that saw Ctrl+S's releases.
  q.push(key(kLeftControl, kActionPress));
  q.push(key('S', kActionPress, kModControl));
  q.push(key('S', kActionRelease, kModControl));
  q.push(key(kLeftControl, kActionRelease));
  q.push(key('A', kActionPress));
  q.push(character('a'));
  q.push(key('A', kActionRelease));
  q.push(key('B', kActionPress));
  q.push(character('b'));
  q.push(key('B', kActionRelease));
  CHECK(frames_of(q) == " P341 P83 | R83 R341 | P65 C97 | R65 P66 C98 | R66");
  // xdotool's Ctrl+S lets go of Ctrl before S, and the press may come in the batch after Ctrl's:
  // Ctrl goes up only in the frame after the one that saw S go down with it.
  q.push(key(kLeftControl, kActionPress));
  CHECK(frames_of(q) == " P341");
  q.push(key('S', kActionPress, kModControl));
  q.push(key(kLeftControl, kActionRelease, kModControl));
  q.push(key('S', kActionRelease));
  CHECK(frames_of(q) == " P83 | R341 R83");
  // Key repeats of a held key are presses of their own; a frame with nothing queued takes nothing.
  q.push(key(kRight, kActionPress));
  q.push(key(kRight, kActionRepeat));
  CHECK(frames_of(q) == " P262 | P262");
  CHECK(q.take_frame().empty());
}

TEST_CASE("keys at rest: ten quick presses step ten frames, and typing after Ctrl+S names the session") {
  const fs::path dir = fs::temp_directory_path() / ("mostyle_input_queue_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  mostyle::test::OffscreenEditor e;
  REQUIRE(e.gl.ok());
  Editor& editor = e.editor;
  ImGuiIO& io = ImGui::GetIO();
  io.KeyMap[ImGuiKey_RightArrow] = kRight;  // as ImGui's GLFW back-end maps them
  io.KeyMap[ImGuiKey_Enter] = kEnter;
  io.KeyMap[ImGuiKey_Escape] = kEscape;
  editor.wait_for_engine();
  editor.init_graphics();
  InputQueue queue;
  auto frame = [&] {
    give_frame(queue, io);
    io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    e.frame();
  };
  auto drain = [&] {
    for (int i = 0; i < 500 && !queue.empty(); ++i) frame();
    frame();
  };
  frame();
  frame();
  const mostyle::ui::ShownMotion* reference = editor.state().reference_take();
  REQUIRE(reference != nullptr);
  const int start = mostyle::ui::frame_at(*reference, editor.state().playback.time_s);
  for (int i = 0; i < 10; ++i) {  // ten taps of the right arrow, all before the next frame
    queue.push(key(kRight, kActionPress));
    queue.push(key(kRight, kActionRelease));
  }
  drain();
  CHECK(mostyle::ui::frame_at(*reference, editor.state().playback.time_s) == start + 10);

  // Ctrl+S, then the name typed at once, then Enter: saved under that name.
  const std::string target = (dir / "day2.mostyle").string();
  queue.push(key(kLeftControl, kActionPress));
  queue.push(key('S', kActionPress, kModControl));
  queue.push(key('S', kActionRelease, kModControl));
  queue.push(key(kLeftControl, kActionRelease));
  for (char c : target) {
    queue.push(key('A', kActionPress));
    queue.push(character(static_cast<unsigned char>(c)));
    queue.push(key('A', kActionRelease));
  }
  queue.push(key(kEnter, kActionPress));
  queue.push(key(kEnter, kActionRelease));
  drain();
  CHECK(fs::exists(target));
  CHECK(editor.session_path() == target);
  editor.shutdown_graphics();
  fs::remove_all(dir);
}

TEST_CASE("input queue: typing into a field, all that was typed goes in one frame, a key that types nothing last") {
  InputQueue q;
  auto type = [&](int k, char c, int mods = 0) {
    q.push(key(k, kActionPress, mods));
    q.push(character(static_cast<unsigned char>(c)));
    q.push(key(k, kActionRelease, mods));
  };
  // "Foo" (Shift for the F, the o twice), then Enter, then "x": Enter ends the frame's typing.
  constexpr int kShift = 340, kBackspace = 259;
  q.push(key(kShift, kActionPress));
  type('F', 'F', kModShift);
  q.push(key(kShift, kActionRelease, kModShift));
  type('O', 'o');
  type('O', 'o');
  q.push(key(kEnter, kActionPress));
  q.push(key(kEnter, kActionRelease));
  type('X', 'x');
  std::string frames;
  while (!q.empty()) {
    if (!frames.empty()) frames += " |";
    for (const KeyEvent& e : q.take_frame(/*typing=*/true)) {
      if (e.kind == KeyEvent::Kind::kChar) frames += " C" + std::to_string(e.codepoint);
      else frames += std::string(e.action == kActionRelease ? " R" : " P") + std::to_string(e.key);
    }
  }
  CHECK(frames == " P340 P70 C70 R70 R340 P79 C111 R79 P79 C111 R79 P257 | R257 P88 C120 R88");
  // Backspace between characters: the characters after it wait for the next frame.
  type('A', 'a');
  q.push(key(kBackspace, kActionPress));
  q.push(key(kBackspace, kActionRelease));
  type('B', 'b');
  CHECK(q.take_frame(true).size() == 4);  // P65 C97 R65 P259
  CHECK(q.take_frame(true).size() == 4);  // R259 P66 C98 R66
  CHECK(q.empty());
  // Not typing: one press a frame, as before.
  type('A', 'a');
  type('B', 'b');
  CHECK(frames_of(q) == " P65 C97 | R65 P66 C98 | R66");
}

TEST_CASE("a path typed quickly into a take's field, then Load clicked at once: the path is loaded whole") {
  mostyle::test::OffscreenEditor e({1280, 720});
  REQUIRE(e.gl.ok());
  Editor& editor = e.editor;
  ImGuiIO& io = ImGui::GetIO();
  io.KeyMap[ImGuiKey_A] = 'A';  // Ctrl+A: select all in a field
  io.KeyMap[ImGuiKey_Enter] = kEnter;
  editor.wait_for_engine();
  editor.init_graphics();
  InputQueue queue;
  ImVec2 mouse(-FLT_MAX, -FLT_MAX);
  bool button = false;
  auto frame = [&] {
    give_frame(queue, io);
    io.MousePos = mouse;
    io.MouseDown[0] = button;
    e.frame();
  };
  frame();
  frame();
  // Take B's field and its Load button ("##take" and "Load" under PushID(1) in the files panel),
  // found by moving the mouse down the field's column, then along its row.
  const ImGuiWindow* files = ImGui::FindWindowByName(mostyle::ui::panel_title(mostyle::ui::PanelId::kFiles));
  REQUIRE(files != nullptr);
  const int take = 1;
  const ImGuiID field_id = ImHashStr("##take", 0, ImHashData(&take, sizeof take, files->ID));
  const ImGuiID load_id = ImHashStr("Load", 0, ImHashData(&take, sizeof take, files->ID));
  ImVec2 field(-1.0f, -1.0f), load(-1.0f, -1.0f);
  for (float y = files->Pos.y; y < files->Pos.y + 160.0f && field.x < 0.0f; y += 3.0f) {
    mouse = ImVec2(files->Pos.x + 3.0f * ImGui::GetFontSize(), y);
    frame();
    if (GImGui->HoveredId == field_id) field = mouse;
  }
  REQUIRE(field.x >= 0.0f);
  for (float x = field.x; x < files->Pos.x + files->Size.x && load.x < 0.0f; x += 4.0f) {
    mouse = ImVec2(x, field.y);
    frame();
    if (GImGui->HoveredId == load_id) load = mouse;
  }
  REQUIRE(load.x >= 0.0f);
  // Click into the field, select all it holds (Ctrl+A).
  mouse = field;
  button = true;
  frame();
  button = false;
  frame();
  queue.push(key(kLeftControl, kActionPress));
  queue.push(key('A', kActionPress, kModControl));
  queue.push(key('A', kActionRelease, kModControl));
  queue.push(key(kLeftControl, kActionRelease, kModControl));
  for (int i = 0; i < 10 && !queue.empty(); ++i) frame();
  frame();
  REQUIRE(io.WantTextInput);
  // The path typed between two frames, and Load pressed before the next.
  const std::string path = mostyle::test::asset("motions/cmu142_walk_joy.bvh");
  REQUIRE(path.size() > 40);
  for (char c : path) {
    const int k = std::toupper(static_cast<unsigned char>(c));
    queue.push(key(k, kActionPress));
    queue.push(character(static_cast<unsigned char>(c)));
    queue.push(key(k, kActionRelease));
  }
  mouse = load;
  button = true;
  frame();
  button = false;
  frame();
  mouse = ImVec2(-FLT_MAX, -FLT_MAX);
  for (int i = 0; i < 500 && !queue.empty(); ++i) frame();
  const std::vector<std::string> asked = editor.engine().requested_files();
  REQUIRE(asked.size() == 2);
  CHECK(asked[1] == path);
  editor.shutdown_graphics();
}
