// Keys handed to ImGui at the pace of frames (app/input_queue.h): no press lost at rest, and
// what is typed after a shortcut lands in the field the shortcut opens.
#include "app/input_queue.h"

#include <cfloat>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include <catch2/catch.hpp>
#include <imgui.h>

#include "tests/app/offscreen_editor.h"
#include "tests/test_data.h"

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
  // What the GLFW back-end's callbacks do with an event (imgui_impl_glfw 1.86).
  auto frame = [&] {
    for (const KeyEvent& ev : queue.take_frame()) {
      if (ev.kind == KeyEvent::Kind::kChar) {
        io.AddInputCharacter(ev.codepoint);
        continue;
      }
      if (ev.action == kActionPress) io.KeysDown[ev.key] = true;
      if (ev.action == kActionRelease) io.KeysDown[ev.key] = false;
      io.KeyCtrl = io.KeysDown[kLeftControl];
    }
    io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    e.frame();
  };
  auto drain = [&] {
    for (int i = 0; i < 500 && !queue.empty(); ++i) frame();
    frame();
  };
  frame();
  frame();
  const mostyle::ui::Take* reference = editor.state().reference_take();
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
