// The editor shell: its command line, loading takes without a GL context, and the two
// programs end to end (offscreen screenshot; no display without --offscreen).
#include "app/editor/editor.h"
#include "app/editor/editor_options.h"
#include "app/editor/imgui_context.h"

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <imgui.h>
#include <imgui_internal.h>  // ImGui::FindWindowByName

#include "tests/app/editor/offscreen_editor.h"
#include "tests/render/osmesa_context.h"

#include "app/live/tcp.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/live/axis_stream.h"
#include "render/png_io.h"
#include "tests/test_data.h"
#include "ui/model/live_style_spec.h"
#include "ui/panels/export_dialog.h"
#include "ui/panels/layout.h"

using namespace mostyle::app;
namespace fs = std::filesystem;

namespace {
ParseResult parse(std::vector<const char*> args) {
  args.insert(args.begin(), "mostyle");
  return parse_editor_options(static_cast<int>(args.size()), args.data());
}

// Loads bundled walks (motions/NAME.bvh) as the Files panel does, new takes at weight 0, and
// waits for the worker to prepare them.
void load_walks(Editor& editor, const std::vector<std::string>& names) {
  std::vector<std::string> files;
  for (const std::string& name : names) files.push_back(mostyle::test::asset("motions/" + name + ".bvh"));
  editor.engine().load_files(files, mostyle::ui::WeightsOf::kNewTakes);
  editor.wait_for_engine();
  REQUIRE(editor.engine().takes() != nullptr);
  REQUIRE(editor.engine().takes()->size() == static_cast<int>(names.size()));
}

// Runs a shell command; returns its exit status and (if asked) what it wrote on stderr.
int run(const std::string& command, std::string* stderr_text = nullptr) {
  // One file per test process: ctest runs this program's test cases side by side.
  const std::string err = (fs::temp_directory_path() / ("mostyle_editor_test_" + std::to_string(::getpid()) + ".err")).string();
  int status = std::system((command + " 2>" + err).c_str());
  if (stderr_text) {
    stderr_text->clear();
    if (std::FILE* f = std::fopen(err.c_str(), "r")) {
      char buffer[512];
      while (std::fgets(buffer, sizeof buffer, f)) *stderr_text += buffer;
      std::fclose(f);
    }
  }
  fs::remove(err);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A fresh folder in the temporary one, named after `name` and this process, removed with it.
struct ScratchDir {
  fs::path dir;
  explicit ScratchDir(const std::string& name)
      : dir(fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~ScratchDir() { fs::remove_all(dir); }
  std::string path(const std::string& file) const { return (dir / file).string(); }
  // Writes `text` to `file` in the folder; its path.
  std::string write(const std::string& file, const char* text) const {
    if (std::FILE* f = std::fopen(path(file).c_str(), "w")) {
      std::fputs(text, f);
      std::fclose(f);
    }
    return path(file);
  }
};
}  // namespace

TEST_CASE("editor options: files and flags, both spellings") {
  ParseResult r = parse({"a.bvh", "--alpha", "0.25", "--components=7", "--sparsity", "0.5", "--frame", "12",
                         "b.bvh", "--screenshot", "out.png"});
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.files == std::vector<std::string>{"a.bvh", "b.bvh"});
  CHECK(r.options.initial.weights == std::vector<double>{0.75, 0.25});  // --alpha: a pair's weights
  CHECK(r.options.initial.parameters.components == 7);
  CHECK(r.options.initial.parameters.sparsity == 0.5);
  CHECK(r.options.initial.frame == 12);
  CHECK(r.options.screenshot_path == "out.png");
  CHECK_FALSE(r.options.offscreen);
}

TEST_CASE("editor options: --window-size sets the window and screenshot size, --paused starts paused") {
  ParseResult r = parse({"--window-size", "1920x1080", "--paused"});
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.width == 1920);
  CHECK(r.options.height == 1080);
  CHECK(r.options.initial.paused);
  r = parse({"--window-size=2560X1440"});
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.width == 2560);
  CHECK(r.options.height == 1440);
  CHECK_FALSE(r.options.initial.paused);
  r = parse({});
  CHECK(r.options.width == 1280);
  CHECK(r.options.height == 720);
  // The editor starts paused without a GL context; playing by default.
  EditorOptions options;
  options.files = {"/nonexistent/a.bvh"};
  options.initial.paused = true;
  CHECK_FALSE(Editor(options).state().playback.playing);
  options.initial.paused = false;
  CHECK(Editor(options).state().playback.playing);
}

TEST_CASE("editor options: defaults are the paper's, and --help") {
  ParseResult r = parse({});
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.files.empty());
  CHECK(r.options.initial.weights.empty());  // equal weights: a pair's alpha 0.5
  CHECK(r.options.initial.parameters.components == 10);
  CHECK(r.options.initial.parameters.sparsity == 0.1);
  CHECK(parse({"--help"}).status == ParseStatus::kHelp);
  CHECK(parse({"-h"}).status == ParseStatus::kHelp);
  CHECK_THAT(editor_usage(), Catch::Contains("--offscreen") && Catch::Contains("--screenshot"));
  CHECK_THAT(editor_usage(), Catch::Contains("--window-size WxH") && Catch::Contains("--paused"));
  // --help lists every key the shortcuts window (F1) lists.
  REQUIRE_FALSE(editor_shortcuts().empty());
  for (const ShortcutHelp& k : editor_shortcuts()) CHECK_THAT(editor_usage(), Catch::Contains(k.shortcut) && Catch::Contains(k.action));
}

TEST_CASE("editor options: bad values and unknown flags are usage errors that say which") {
  struct Case {
    std::vector<const char*> args;
    const char* mentions;
  };
  const std::vector<Case> cases = {
      {{"--alpha", "1.6"}, "--alpha"},      {{"--alpha", "x"}, "--alpha"},
      {{"--alpha"}, "--alpha"},             {{"--components", "0"}, "--components"},
      {{"--components", "2.5"}, "--components"}, {{"--sparsity", "0"}, "--sparsity"},
      {{"--frame", "-1"}, "--frame"},       {{"--screenshot"}, "--screenshot"},
      {{"--bogus"}, "--bogus"},             {{"-x"}, "-x"},
      {{"--offscreen"}, "--screenshot"},    {{"--offscreen=1", "--screenshot", "a.png"}, "--offscreen"},
      {{"--window-size"}, "--window-size"}, {{"--window-size", "1280"}, "--window-size"},
      {{"--window-size", "1280x"}, "--window-size"}, {{"--window-size", "x720"}, "--window-size"},
      {{"--window-size", "100x100"}, "--window-size"}, {{"--window-size", "1280x720x3"}, "--window-size"},
      {{"--window-size", "-1280x720"}, "--window-size"}, {{"--window-size=99999x720"}, "--window-size"},
      {{"--paused=yes"}, "--paused"},
  };
  for (const Case& c : cases) {
    ParseResult r = parse(c.args);
    INFO(c.args.front());
    CHECK(r.status == ParseStatus::kUsageError);
    CHECK_THAT(r.error, Catch::Contains(c.mentions));
  }
}

TEST_CASE("the editor loads the pair on the worker, and a load error keeps the pair on the floor") {
  EditorOptions options;
  options.files = {mostyle::test::asset("motions/cmu142_walk_happy.bvh"),
                   mostyle::test::asset("motions/cmu142_walk_marching.bvh")};
  options.initial.parameters.components = 6;
  options.initial.frame = 12;
  Editor editor(options);  // no GL context needed; returns before the worker is done
  editor.wait_for_engine();
  const auto& takes = editor.state().shown;
  REQUIRE(takes.size() == 3);  // A, B on A's timeline, the blend
  for (const auto& t : takes) {
    CHECK(t.ok());
    CHECK(t.frames() == takes[0].frames());
    double lowest = 1e30;
    for (Eigen::Index j = 0; 3 * j < t.positions.cols(); ++j) lowest = std::min(lowest, t.positions.col(3 * j + 1).minCoeff());
    CHECK(lowest == Approx(0.0).margin(0.05 * t.size));  // on A's floor
    CHECK(t.size > 10.0f);  // CMU units: about 30 tall
  }
  CHECK(editor.state().reference_take() == &takes[0]);
  CHECK(mostyle::ui::frame_at(takes[0], editor.state().playback.time_s) == 12);

  editor.engine().load("/nonexistent/walk.bvh", mostyle::test::asset("motions/cmu142_walk_marching.bvh"));
  editor.wait_for_engine();
  CHECK_THAT(editor.engine().error(), Catch::Contains("/nonexistent/walk.bvh"));
  CHECK(editor.state().shown.size() == 3);
}

TEST_CASE("editor options and loads: MOSTYLE_MAX_MEMORY_MB bounds a take's frames, as in mostyle-cli") {
  struct Environment {
    ~Environment() { ::unsetenv("MOSTYLE_MAX_MEMORY_MB"); }
  } restore;
  ::unsetenv("MOSTYLE_MAX_MEMORY_MB");
  CHECK(parse({}).options.max_memory_bytes == mostyle::kDefaultMaxBytes);
  ::setenv("MOSTYLE_MAX_MEMORY_MB", "lots", 1);
  const ParseResult bad = parse({});
  CHECK(bad.status == ParseStatus::kUsageError);
  CHECK(bad.error == "MOSTYLE_MAX_MEMORY_MB: expected a whole number of megabytes from 1 up, found 'lots'");
  ::setenv("MOSTYLE_MAX_MEMORY_MB", "1", 1);
  const ParseResult one = parse({});
  REQUIRE(one.status == ParseStatus::kRun);
  CHECK(one.options.max_memory_bytes == size_t{1} << 20);

  // 30000 frames x 6 channels x 8 bytes: 1.4 MB of frames, over 1 MB.
  std::string text =
      "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation "
      "Xrotation Yrotation\n}\nMOTION\nFrames: 30000\nFrame Time: 0.01\n";
  for (int f = 0; f < 30000; ++f) text += "0 0 0 0 0 0\n";
  const std::string long_take = (fs::temp_directory_path() / ("mostyle_editor_limit_" + std::to_string(::getpid()) + ".bvh")).string();
  { std::ofstream(long_take, std::ios::binary) << text; }
  EditorOptions options = one.options;
  options.files = {long_take, mostyle::test::asset("motions/cmu142_walk_marching.bvh")};
  Editor editor(options);
  editor.wait_for_engine();
  CHECK(editor.engine().error() == long_take + ":8: expected frames within the memory limit of 1 MB, found Frames: "
                                                "30000 of 6 values each (1.4 MB)");
  fs::remove(long_take);
}

TEST_CASE("the editor keeps rendering offscreen for hundreds of frames while decompositions run") {
  const glm::ivec2 size(800, 450);
  mostyle::test::OsMesaContext gl(size);
  REQUIRE(gl.ok());
  ImGuiContextScope imgui(/*persist_layout=*/false);
  EditorOptions options;
  options.initial.parameters.components = 4;
  Editor editor(options);
  editor.init_graphics();
  auto& state = editor.state();
  int frames_while_busy = 0, decompositions_requested = 0;
  Eigen::MatrixXd previous_blend;
  int blend_changes = 0;
  for (int frame = 0; frame < 300; ++frame) {
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(static_cast<float>(size.x), static_cast<float>(size.y));
    io.DeltaTime = 1.0f / 60.0f;
    if (frame % 60 == 30 && !state.shown.empty()) {  // a new k or sparsity: re-decomposition
      state.document.parameters.components = 6 + 2 * ((frame / 60) % 4);
      state.document.parameters.sparsity = frame % 120 == 30 ? 0.2 : 0.3;
      ++decompositions_requested;
    }
    set_pair_alpha(state.document, 0.5 + 0.5 * std::sin(frame * 0.1));  // blended in this very frame
    if (frame % 90 == 45) state.document.overlay = !state.document.overlay;
    editor.frame(FrameInput{size, 1.0f / 60.0f});
    // The frame went on while the decomposition it asked for was not there yet.
    if (editor.engine().decomposition_outdated()) ++frames_while_busy;
    if (state.shown.size() == 3) {
      const Eigen::MatrixXd& blend = state.shown[2].positions;
      // Alpha changes the blend's poses and, with its timing, its length.
      if (previous_blend.size() > 0 && (previous_blend.rows() != blend.rows() || previous_blend != blend)) ++blend_changes;
      previous_blend = blend;
    }
  }
  editor.wait_for_engine();
  editor.frame(FrameInput{size, 1.0f / 60.0f});
  editor.shutdown_graphics();
  CHECK(decompositions_requested >= 4);
  CHECK(frames_while_busy > 0);  // frames went on while the worker worked
  CHECK(blend_changes > 100);    // and the blend followed alpha
  CHECK(editor.engine().error().empty());
  const auto& shown = editor.engine().snapshot().decompose_params;
  CHECK(shown.components == state.document.parameters.components);  // the last request won
  CHECK(shown.sparsity == state.document.parameters.sparsity);
}

TEST_CASE("keys: F1 and ? show the keys list, Esc hides it, F frames all, Ctrl+0 resets the layout") {
  mostyle::test::OffscreenEditor e;
  REQUIRE(e.gl.ok());
  const glm::ivec2 size = e.size;
  Editor& editor = e.editor;
  editor.wait_for_engine();
  editor.init_graphics();
  auto& state = editor.state();
  ImGuiIO& io = ImGui::GetIO();
  io.KeyMap[ImGuiKey_Escape] = 256;  // as GLFW's back-end maps it (GLFW_KEY_ESCAPE)
  auto frame = [&] { e.frame(); };
  auto press = [&](int key) {
    io.KeysDown[key] = true;
    frame();
    io.KeysDown[key] = false;
    frame();
  };
  auto keys_shown = [&]() {
    const ImGuiWindow* w = ImGui::FindWindowByName("Shortcuts");
    return w != nullptr && w->Active;
  };
  frame();
  frame();
  CHECK_FALSE(state.playback.playing);  // --paused
  CHECK_FALSE(keys_shown());

  press(kKeyboardF1);
  CHECK(state.view.show_shortcuts);
  CHECK(keys_shown());
  io.AddInputCharacter('?');
  frame();
  CHECK_FALSE(state.view.show_shortcuts);
  CHECK_FALSE(keys_shown());
  io.AddInputCharacter('?');
  frame();
  CHECK(keys_shown());
  press(256);
  CHECK_FALSE(keys_shown());

  // Dragging in the viewport turns the camera, never under the floor; F frames all again.
  const float framed_yaw = editor.camera().yaw;
  io.MousePos = ImVec2(480.0f, 230.0f);  // between the columns, above the DTW view: no panel
  frame();
  io.MouseDown[0] = true;
  io.MousePos = ImVec2(560.0f, 200.0f);
  frame();
  io.MousePos = ImVec2(560.0f, 20.0f);  // far up: the eye goes down as far as it may
  frame();
  io.MouseDown[0] = false;
  frame();
  CHECK(editor.camera().yaw != Approx(framed_yaw));
  CHECK(editor.camera().pitch == Approx(mostyle::render::OrbitCamera::kMinPitch));
  CHECK(editor.camera().eye().y > 0.0f);
  io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
  press(kKeyboardF);
  CHECK(editor.camera().yaw == Approx(framed_yaw));
  CHECK(editor.camera().pitch > mostyle::render::OrbitCamera::kMinPitch);

  // A moved panel stays; Ctrl+0 puts it back.
  using mostyle::ui::PanelId;
  const char* files = mostyle::ui::panel_title(PanelId::kFiles);
  const mostyle::ui::PanelRect home = mostyle::ui::compute_layout(
      static_cast<float>(size.x), static_cast<float>(size.y),
      mostyle::ui::playback_bar_height())[static_cast<size_t>(PanelId::kFiles)];
  REQUIRE(ImGui::FindWindowByName(files) != nullptr);
  CHECK(ImGui::FindWindowByName(files)->Pos.x == Approx(home.x).margin(1.0f));
  ImGui::SetWindowPos(files, ImVec2(420.0f, 120.0f));
  frame();
  CHECK(ImGui::FindWindowByName(files)->Pos.x == 420.0f);
  io.KeyCtrl = true;
  press(kKeyboardZero);
  io.KeyCtrl = false;
  CHECK(ImGui::FindWindowByName(files)->Pos.x == Approx(home.x).margin(1.0f));
  CHECK(ImGui::FindWindowByName(files)->Pos.y == Approx(home.y).margin(1.0f));

  // With loop off, playback stops on the last frame: the button reads Play again.
  state.playback.loop = false;
  state.playback.playing = true;
  for (int i = 0; i < 20 && state.playback.playing; ++i) {
    state.playback.time_s = mostyle::ui::take_length_s(*state.reference_take()) - 0.001;
    frame();
  }
  CHECK_FALSE(state.playback.playing);
  CHECK(mostyle::ui::frame_at(*state.reference_take(), state.playback.time_s) == state.reference_take()->frames() - 1);

  // Ctrl+E opens the export dialog; it goes when closed.
  auto export_shown = [&]() {
    const ImGuiWindow* w = ImGui::FindWindowByName(mostyle::ui::kExportDialogTitle);
    return w != nullptr && w->Active;
  };
  CHECK_FALSE(export_shown());
  io.KeyCtrl = true;
  press(kKeyboardE);
  io.KeyCtrl = false;
  CHECK(state.view.show_export);
  CHECK(export_shown());
  state.view.show_export = false;
  frame();
  CHECK_FALSE(export_shown());
  editor.shutdown_graphics();
}

TEST_CASE("mostyle-offscreen writes a 1280x720 screenshot of the editor") {
  const std::string out = (fs::temp_directory_path() / "mostyle_editor_test_offscreen.png").string();
  fs::remove(out);
  std::string err;
  CHECK(run(std::string(MOSTYLE_OFFSCREEN_EXE) + " --screenshot " + out + " --frame 30", &err) == 0);
  INFO(err);
  REQUIRE(fs::exists(out));
  mostyle::render::Image image = mostyle::render::read_png(out);
  CHECK(image.width == 1280);
  CHECK(image.height == 720);
  // Not one flat colour: skeletons, floor and panels are there.
  size_t distinct = 0;
  for (size_t i = 4; i < image.rgba.size(); i += 4 * 97)
    distinct += image.rgba[i] != image.rgba[0] || image.rgba[i + 2] != image.rgba[2] ? 1 : 0;
  CHECK(distinct > 100);
  fs::remove(out);
}

TEST_CASE("mostyle-offscreen with a take that cannot be read: its one sentence, exit 1, no screenshot") {
  const ScratchDir scratch("mostyle_editor_test_bad_take");
  const std::string bad = scratch.write("bad.bvh", "HIERARCHY\nnot a joint\n");
  const std::string png = scratch.path("out.png");
  std::string err;
  CHECK(run(std::string("env ASAN_OPTIONS=detect_leaks=0 timeout 120 ") + MOSTYLE_OFFSCREEN_EXE + " " + bad +
                " --screenshot " + png,
            &err) == 1);
  CHECK_THAT(err, Catch::StartsWith("mostyle: " + bad + ":2: "));
  CHECK(std::count(err.begin(), err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(png));
}

TEST_CASE("mostyle without a display says so in one line and exits 1, --offscreen still works") {
  std::string err;
  CHECK(run(std::string("env -u DISPLAY -u WAYLAND_DISPLAY ") + MOSTYLE_EXE, &err) == 1);
  CHECK(err == "mostyle: no display; run under xvfb-run or pass --offscreen\n");
  const std::string out = (fs::temp_directory_path() / "mostyle_editor_test_exec.png").string();
  fs::remove(out);
  // Leaks are checked in-process by the other editor tests; here only the exit path counts (Mesa's
  // JIT threads can leave allocations LeakSanitizer cannot attribute to a library).
  CHECK(run(std::string("env -u DISPLAY ASAN_OPTIONS=detect_leaks=0 ") + MOSTYLE_EXE + " --offscreen --screenshot " + out,
            &err) == 0);
  INFO(err);
  CHECK(fs::exists(out));
  fs::remove(out);
  CHECK(run(std::string(MOSTYLE_EXE) + " --alpha 7", &err) == 2);
  CHECK(err == "mostyle: --alpha: expected a number from -0.5 to 1.5, got '7'\n");
  CHECK(run(std::string(MOSTYLE_EXE) + " --window-size 12x7", &err) == 2);
  CHECK(err == "mostyle: --window-size: expected WIDTHxHEIGHT in pixels, each 320 to 16384 (e.g. 1920x1080), got '12x7'\n");
}

TEST_CASE("a screenshot takes the size --window-size gives") {
  const std::string out = (fs::temp_directory_path() / "mostyle_editor_test_size.png").string();
  fs::remove(out);
  std::string err;
  CHECK(run(std::string("env ASAN_OPTIONS=detect_leaks=0 ") + MOSTYLE_OFFSCREEN_EXE + " --screenshot " + out +
                " --window-size 960x540 --paused",
            &err) == 0);
  INFO(err);
  REQUIRE(fs::exists(out));
  mostyle::render::Image image = mostyle::render::read_png(out);
  CHECK(image.width == 960);
  CHECK(image.height == 540);
  fs::remove(out);
}

TEST_CASE("editor options: a .mostyle argument opens that session, alone") {
  ParseResult r = parse({"day.mostyle", "--paused"});
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.session_path == "day.mostyle");
  CHECK(r.options.files.empty());
  CHECK(parse({"work/Day.MOSTYLE"}).options.session_path == "work/Day.MOSTYLE");
  CHECK(parse({"a.bvh"}).options.session_path.empty());
  r = parse({"a.bvh", "day.mostyle"});
  CHECK(r.status == ParseStatus::kUsageError);
  CHECK_THAT(r.error, Catch::Contains("day.mostyle"));
  CHECK_THAT(editor_usage(), Catch::Contains("SESSION.mostyle"));
}

TEST_CASE("sessions and undo: Ctrl+Z / Ctrl+Y undo and redo a load, a saved session opens as it was") {
  namespace ui = mostyle::ui;
  const glm::ivec2 size(960, 540);
  mostyle::test::OsMesaContext gl(size);
  REQUIRE(gl.ok());
  ImGuiContextScope imgui(/*persist_layout=*/false);
  const fs::path dir = fs::temp_directory_path() / "mostyle_editor_test_sessions";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string happy = mostyle::test::asset("motions/cmu142_walk_happy.bvh");
  const std::string marching = mostyle::test::asset("motions/cmu142_walk_marching.bvh");
  const std::string joy = mostyle::test::asset("motions/cmu142_walk_joy.bvh");
  const std::string day = (dir / "day.mostyle").string();
  EditorOptions options;
  options.files = {happy, marching};
  options.initial.parameters.components = 4;
  options.initial.paused = true;
  options.recent_path = (dir / "config" / "recent.json").string();
  ImGuiIO& io = ImGui::GetIO();
  io.KeyMap[ImGuiKey_Escape] = 256;  // as GLFW's back-end maps it (GLFW_KEY_ESCAPE)
  auto frame = [&](Editor& editor) {
    io.DisplaySize = ImVec2(static_cast<float>(size.x), static_cast<float>(size.y));
    io.DeltaTime = 1.0f / 60.0f;
    editor.frame(FrameInput{size, 1.0f / 60.0f});
  };
  auto press = [&](Editor& editor, int key, bool ctrl, bool shift) {
    io.KeyCtrl = ctrl;
    io.KeyShift = shift;
    io.KeysDown[key] = true;
    frame(editor);
    io.KeysDown[key] = false;
    frame(editor);
    io.KeyCtrl = io.KeyShift = false;
  };
  auto shown = [](const char* window) {
    const ImGuiWindow* w = ImGui::FindWindowByName(window);
    return w != nullptr && w->Active;
  };

  ui::SessionFile saved;
  {
    Editor editor(options);
    editor.wait_for_engine();
    editor.init_graphics();
    frame(editor);
    frame(editor);
    CHECK_FALSE(editor.edits().can_undo());
    // The pair that loaded is a recent take, kept across restarts.
    REQUIRE_FALSE(ui::read_recent_files(options.recent_path).takes.empty());
    CHECK(ui::read_recent_files(options.recent_path).takes.front() == happy);

    // A pair dropped on the window loads: one step. Ctrl+Z brings the first pair back, Ctrl+Y
    // the dropped one again, Ctrl+Shift+Z then has nothing left to redo.
    editor.drop_files({joy, marching});
    frame(editor);
    editor.wait_for_engine();
    frame(editor);
    REQUIRE(editor.engine().snapshot().paths[0] == joy);
    CHECK(editor.edits().can_undo());
    press(editor, kKeyboardZ, true, false);
    editor.wait_for_engine();
    frame(editor);
    CHECK(editor.engine().snapshot().paths[0] == happy);
    CHECK(editor.edits().can_redo());
    press(editor, kKeyboardY, true, false);
    editor.wait_for_engine();
    frame(editor);
    CHECK(editor.engine().snapshot().paths[0] == joy);
    press(editor, kKeyboardZ, true, true);
    CHECK_FALSE(editor.edits().can_redo());
    CHECK(editor.engine().snapshot().paths[0] == joy);

    // Saved: the takes, every parameter, the camera and the playback. ".mostyle" is added.
    set_pair_alpha(editor.state().document, 0.8);
    editor.state().document.overlay = true;
    frame(editor);
    CHECK_FALSE(editor.save_session((dir / "day.bvh").string()));  // never over a take
    REQUIRE(editor.save_session((dir / "day").string()));
    CHECK(editor.session_path() == day);
    CHECK_THAT(editor.session_message(), Catch::Contains("day.mostyle"));
    CHECK(ui::read_recent_files(options.recent_path).sessions.front() == day);
    // Ctrl+S saves there again without asking; Ctrl+O asks which session, Esc closes it.
    fs::remove(day);
    press(editor, kKeyboardS, true, false);
    CHECK(fs::exists(day));
    CHECK_FALSE(shown("Save session"));
    press(editor, kKeyboardO, true, false);
    CHECK(shown("Open session"));
    press(editor, 256, false, false);
    CHECK_FALSE(shown("Open session"));
    saved = ui::read_session_file(day);
    editor.shutdown_graphics();
  }
  REQUIRE(saved.camera.has_value());
  CHECK(pair_alpha(saved.document) == 0.8);
  CHECK(saved.document.overlay);
  CHECK(saved.document.files == std::vector<std::string>{joy, marching});

  // A new editor opens it as it was: the takes, the parameters, the playback, the camera.
  EditorOptions again;
  again.session_path = day;
  again.recent_path = options.recent_path;
  Editor reopened(again);
  CHECK(reopened.session_path() == day);
  CHECK_FALSE(reopened.session_message_is_error());
  CHECK(pair_alpha(reopened.state().document) == 0.8);
  CHECK(reopened.state().document.parameters.components == 4);
  CHECK(reopened.state().document.overlay);
  CHECK(reopened.recent_files().sessions.front() == day);
  reopened.wait_for_engine();
  reopened.init_graphics();
  frame(reopened);
  CHECK(reopened.engine().snapshot().paths[0] == joy);
  CHECK(reopened.state().playback.time_s == saved.playback.time_s);
  CHECK_FALSE(reopened.state().playback.playing);
  CHECK(reopened.camera().yaw == Approx(saved.camera->yaw));
  CHECK(reopened.camera().pitch == Approx(saved.camera->pitch));
  CHECK(reopened.camera().distance == Approx(saved.camera->distance));

  // A malformed session: one line naming the file and the line, and nothing changes.
  const std::string bad = (dir / "bad.mostyle").string();
  if (std::FILE* f = std::fopen(bad.c_str(), "w")) {
    std::fputs("{\n  \"version\": 1,\n  \"parameters\": {\"alpha\": 2}\n}\n", f);
    std::fclose(f);
  }
  CHECK_FALSE(reopened.open_session(bad));
  CHECK_THAT(reopened.session_message(), Catch::StartsWith(bad + ":3: "));
  CHECK(reopened.session_message().find('\n') == std::string::npos);
  CHECK(pair_alpha(reopened.state().document) == 0.8);
  CHECK(reopened.session_path() == day);

  // A session whose take moved away: it opens with its other take, names the file, restores
  // the rest, and is no file to save to (its file is never written without the take). No undo
  // reaches back before an open.
  ui::SessionFile moved = saved;
  moved.document.files = {(dir / "gone.bvh").string(), marching};
  set_pair_alpha(moved.document, 0.1);
  ui::write_session_file((dir / "moved.mostyle").string(), moved);
  const std::string moved_text = [&] {
    std::ifstream in(dir / "moved.mostyle");
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }();
  CHECK(reopened.open_session((dir / "moved.mostyle").string()));
  CHECK(reopened.session_message_is_error());
  CHECK_THAT(reopened.session_message(), Catch::Contains("gone.bvh") && Catch::Contains("left as it is"));
  CHECK(reopened.session_path().empty());
  reopened.wait_for_engine();
  frame(reopened);
  CHECK(reopened.engine().snapshot().paths[0] == marching);
  CHECK_FALSE(reopened.edits().can_undo());
  press(reopened, kKeyboardS, true, false);  // Ctrl+S asks where, in the session's folder
  CHECK(shown("Save session"));
  press(reopened, 256, false, false);
  std::ifstream unchanged(dir / "moved.mostyle");
  CHECK(std::string((std::istreambuf_iterator<char>(unchanged)), std::istreambuf_iterator<char>()) == moved_text);
  reopened.shutdown_graphics();
  fs::remove_all(dir);
}

TEST_CASE("at rest the editor still draws the frames a dialog asked for needs to show, then rests") {
  mostyle::test::OffscreenEditor e({800, 450});
  REQUIRE(e.gl.ok());
  Editor& editor = e.editor;
  editor.wait_for_engine();
  editor.init_graphics();
  for (int i = 0; i < 5; ++i) e.frame();
  CHECK_FALSE(editor.settling());
  // Ctrl+O's command, as a button gives it: the dialog opens over the next frames, which the
  // window draws without input (settling), and it is whole once they are drawn.
  editor.command_open();
  CHECK_FALSE(editor.animating());
  e.frame();
  int frames = 1;
  for (; editor.settling() && frames < 10; ++frames) e.frame();
  CHECK(frames >= 2);
  CHECK_FALSE(editor.settling());
  const ImGuiWindow* dialog = ImGui::FindWindowByName("Open session");
  REQUIRE(dialog != nullptr);
  CHECK(dialog->Active);
  CHECK(dialog->HiddenFramesCannotSkipItems == 0);
  CHECK(dialog->Size.x > 100.0f);
  editor.shutdown_graphics();
}

TEST_CASE("at rest, a finished decomposition wakes the editor and shows at once (no input needed)") {
  mostyle::test::OffscreenEditor e({800, 450});
  REQUIRE(e.gl.ok());
  Editor& editor = e.editor;
  std::atomic<int> wakes{0};
  editor.set_wake([&] { ++wakes; });
  editor.wait_for_engine();
  editor.init_graphics();
  auto frame = [&] { e.frame(); };
  // Paused with the engine idle and everything taken up: at rest, the window may wait.
  for (int i = 0; i < 3 && editor.animating(); ++i) {
    editor.engine().wait_idle(editor.state());
    frame();
  }
  REQUIRE_FALSE(editor.animating());
  // Nor is ImGui still laying anything out: the window may wait for input.
  for (int i = 0; i < 3 && editor.settling(); ++i) frame();
  CHECK_FALSE(editor.settling());
  // A new k (as the slider gives it): the worker decomposes while no input comes.
  const int before = wakes;
  editor.state().document.parameters.components = 6;
  editor.engine().sync(editor.state());
  CHECK(editor.animating());  // the worker has work
  const auto t0 = std::chrono::steady_clock::now();
  while (editor.engine().status().stage != mostyle::WorkerStage::kIdle || editor.engine().status().pending) {
    REQUIRE(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60));
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  // The worker is done and nothing has polled it: the window is woken, and the next frame is
  // drawn (animating) and shows the new components, not the old ones with "decomposing 80%".
  const auto t1 = std::chrono::steady_clock::now();
  while (wakes == before && std::chrono::steady_clock::now() - t1 < std::chrono::seconds(10))
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  CHECK(wakes > before);
  CHECK(editor.animating());
  frame();
  CHECK(editor.engine().snapshot().decompose_params.components == 6);
  CHECK_FALSE(editor.engine().decomposition_outdated());
  editor.shutdown_graphics();
}

TEST_CASE("editor options: --weights and --save-session") {
  ParseResult r = parse({"a.bvh", "b.bvh", "c.bvh", "d.bvh", "--weights", "1.3,-0.5,0.1,0.1"});
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.initial.weights == std::vector<double>{1.3, -0.5, 0.1, 0.1});
  r = parse({"--weights=1/3,2/3"});  // the bundled pair: alpha 2/3
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.initial.weights[1] == Approx(2.0 / 3.0));
  r = parse({"a.bvh", "b.bvh", "c.bvh", "--weights", "0.333334,0.333334,0.333334"});  // within 0.001: normalized
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.initial.weights[0] == Approx(1.0 / 3.0).epsilon(1e-12));
  for (const std::vector<const char*>& bad :
       {std::vector<const char*>{"a.bvh", "b.bvh", "c.bvh", "--weights", "0.5,0.5"},
        std::vector<const char*>{"a.bvh", "b.bvh", "c.bvh", "--weights", "0.5,0.6,0"},
        std::vector<const char*>{"a.bvh", "b.bvh", "c.bvh", "--weights", "2,-0.5,-0.5"},
        std::vector<const char*>{"a.bvh", "b.bvh", "--weights", "1.6,-0.6"},
        std::vector<const char*>{"day.mostyle", "--weights", "0.5,0.5"},
        std::vector<const char*>{"--save-session", "day.bvh"}, std::vector<const char*>{"--save-session"}}) {
    const ParseResult p = parse(bad);
    INFO(p.error);
    CHECK(p.status == ParseStatus::kUsageError);
  }
  // A pair's weights and alpha have the mix's range, as `blend --alpha` has it: B's 1.3 and -0.3.
  r = parse({"a.bvh", "b.bvh", "--weights", "-0.3,1.3"});
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.initial.weights == std::vector<double>{-0.3, 1.3});
  r = parse({"a.bvh", "b.bvh", "--alpha", "-0.5"});
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.initial.weights == std::vector<double>{1.5, -0.5});
  r = parse({"--save-session", "out/day", "--paused"});
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.save_session_path == "out/day");
}

TEST_CASE("a session given on the command line that cannot be opened: one line, exit 1, nothing else opens") {
  const ScratchDir scratch("mostyle_editor_test_bad_session");
  const std::string bad = scratch.write("bad.mostyle", "{\n  \"version\": 1,\n  \"parameters\": {\"alpha\": 2}\n}\n");
  const std::string png = scratch.path("out.png");
  std::string err;
  CHECK(run(std::string("env ASAN_OPTIONS=detect_leaks=0 ") + MOSTYLE_OFFSCREEN_EXE + " " + bad + " --screenshot " + png,
            &err) == 1);
  CHECK(err == "mostyle: " + bad + ":3: parameters.alpha: expected a number from -0.5 to 1.5, found 2\n");
  CHECK_FALSE(fs::exists(png));
  CHECK(run(std::string("env -u DISPLAY -u WAYLAND_DISPLAY ") + MOSTYLE_EXE + " " + scratch.path("none.mostyle"),
            &err) == 1);
  CHECK_THAT(err, Catch::StartsWith("mostyle: " + scratch.path("none.mostyle") + ": cannot read"));
}

TEST_CASE("a state set up by flags, saved with --save-session, reopens to the same picture") {
  const fs::path dir = fs::temp_directory_path() / ("mostyle_editor_test_scripted_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string happy = mostyle::test::asset("motions/cmu142_walk_happy.bvh");
  const std::string marching = mostyle::test::asset("motions/cmu142_walk_marching.bvh");
  const std::string joy = mostyle::test::asset("motions/cmu142_walk_joy.bvh");
  const std::string clumsy = mostyle::test::asset("motions/cmu142_walk_clumsy.bvh");
  struct Case {
    std::string name, takes, flags;
  };
  // A palette with a weight beyond 1 (the sliders allow -0.5 to 1.5), and a pair at alpha 0.7.
  const std::vector<Case> cases = {
      {"palette", happy + " " + marching + " " + joy + " " + clumsy, "--weights 1.3,-0.5,0.1,0.1"},
      {"pair", happy + " " + marching, "--weights 0.3,0.7"}};
  const std::string program = std::string("env ASAN_OPTIONS=detect_leaks=0 ") + MOSTYLE_OFFSCREEN_EXE;
  for (const Case& c : cases) {
    INFO(c.name);
    const std::string session = (dir / (c.name + ".mostyle")).string();
    const std::string first = (dir / (c.name + "_set_up.png")).string();
    const std::string again = (dir / (c.name + "_reopened.png")).string();
    std::string err;
    REQUIRE(run(program + " " + c.takes + " " + c.flags + " --components 4 --frame 20 --window-size 640x360 --save-session " +
                    session + " --screenshot " + first,
                &err) == 0);
    INFO(err);
    REQUIRE(fs::exists(session));
    const mostyle::ui::SessionFile saved = mostyle::ui::read_session_file(session);
    if (c.name == "palette") CHECK(saved.document.layers[0].weight == Approx(1.3));
    else CHECK(pair_alpha(saved.document) == Approx(0.7));
    REQUIRE(run(program + " " + session + " --window-size 640x360 --screenshot " + again, &err) == 0);
    const mostyle::render::Image a = mostyle::render::read_png(first), b = mostyle::render::read_png(again);
    REQUIRE(a.rgba.size() == b.rgba.size());
    size_t differing = 0;
    for (size_t i = 0; i < a.rgba.size(); i += 4)
      differing += a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2];
    CHECK(differing == 0);
  }
  fs::remove_all(dir);
}

namespace {
// How much the camera looks along the line from take A to take B (x, z): |cos| of the angle
// between its view and that line, 0 looking straight across, 1 looking along it.
double looking_along_lanes(mostyle::test::OffscreenEditor& e) {
  const mostyle::ui::EditorState& s = e.editor.state();
  REQUIRE(s.shown.size() == 3);
  auto hips = [&](const mostyle::ui::ShownMotion& t) {
    const Eigen::Index f = mostyle::ui::frame_at(t, s.playback.time_s);
    return Eigen::Vector2d(t.positions(f, 0), t.positions(f, 2));
  };
  const Eigen::Vector2d across = hips(s.shown[1]) - hips(s.shown[0]);
  const glm::vec3 f = e.editor.camera().forward();
  const Eigen::Vector2d view(f.x, f.z);
  REQUIRE(across.norm() > 0.0);
  REQUIRE(view.norm() > 0.0);
  return std::abs(across.normalized().dot(view.normalized()));
}
}  // namespace

TEST_CASE("the first view looks across the lanes, the takes apart: the bundled pair and an FBX pair") {
  std::vector<std::vector<std::string>> pairs = {{}};
  const std::string happy = mostyle::test::shared_motion("formats/cmu142_walk_happy_30fps.fbx");
  const std::string joy = mostyle::test::shared_motion("formats/cmu142_walk_joy.fbx");
  if (!happy.empty() && fs::exists(happy) && fs::exists(joy)) pairs.push_back({happy, joy});
  else WARN("skipped the FBX pair: ../shared/motions/formats is absent");
  for (const std::vector<std::string>& files : pairs) {
    CAPTURE(files);
    EditorOptions options = mostyle::test::paused_small_pair();
    options.files = files;
    mostyle::test::OffscreenEditor e({1280, 720}, options);
    REQUIRE(e.gl.ok());
    e.editor.wait_for_engine();
    REQUIRE(e.editor.engine().error().empty());
    e.editor.init_graphics();
    for (int i = 0; i < 3; ++i) e.frame();
    // A three-quarter view: within 45 degrees of looking straight across.
    CHECK(looking_along_lanes(e) < std::cos(0.25 * M_PI));
    e.editor.shutdown_graphics();
  }
}

TEST_CASE("paused, a change that moves the result moves the view with it; at rest the view stays") {
  mostyle::test::OffscreenEditor e({1280, 720});
  REQUIRE(e.gl.ok());
  Editor& editor = e.editor;
  editor.wait_for_engine();
  editor.init_graphics();
  mostyle::ui::EditorState& s = editor.state();
  const mostyle::ui::ShownMotion& blend = s.shown[mostyle::ui::result_index(2)];
  set_pair_alpha(s.document, 0.0);
  for (int i = 0; i < 3; ++i) e.frame();
  s.playback.time_s = (blend.frames() - 0.5) / blend.rate();  // the last frame: far from the start
  for (int i = 0; i < 3; ++i) e.frame();
  REQUIRE_FALSE(s.playback.playing);
  // The takes' mean hips (x, z) against the camera's target.
  auto hips = [&] {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (const mostyle::ui::ShownMotion& t : s.shown) {
      const Eigen::Index f = mostyle::ui::frame_at(t, s.playback.time_s);
      sum += Eigen::Vector2d(t.positions(f, 0), t.positions(f, 2));
    }
    return Eigen::Vector2d(sum / static_cast<double>(s.shown.size()));
  };
  auto target = [&] { return Eigen::Vector2d(editor.camera().target.x, editor.camera().target.z); };
  const Eigen::Vector2d before = hips(), offset = target() - before;
  for (int i = 0; i < 3; ++i) e.frame();  // at rest: nothing moves
  CHECK((target() - before - offset).norm() < 1e-6 * blend.size);
  // All of B: the result ends elsewhere, and the view goes with it.
  set_pair_alpha(s.document, 1.0);
  for (int i = 0; i < 3; ++i) e.frame();
  const Eigen::Vector2d after = hips();
  CAPTURE(blend.size, (after - before).norm());
  REQUIRE((after - before).norm() > 0.2 * blend.size);
  CHECK((target() - after - offset).norm() < 0.05 * blend.size);
  editor.shutdown_graphics();
}

namespace {
// An editor on the bundled pair, drawn a few frames; alpha set to `alpha` as a panel's command
// sets it (one undo step) unless negative.
void edit_alpha(mostyle::test::OffscreenEditor& e, double alpha) {
  e.editor.wait_for_engine();
  e.editor.init_graphics();
  for (int i = 0; i < 3; ++i) e.frame();
  if (alpha < 0.0) return;
  set_pair_alpha(e.editor.state().document, alpha);
  e.editor.state().command_edits++;
  for (int i = 0; i < 3; ++i) e.frame();
}
}  // namespace

TEST_CASE("closing with unsaved edits asks Save / Discard / Cancel; Save writes the session, then closes") {
  ScratchDir scratch("mostyle_editor_close");
  {  // Nothing edited: closes at once, nothing asked.
    mostyle::test::OffscreenEditor e({640, 360});
    REQUIRE(e.gl.ok());
    edit_alpha(e, -1.0);
    e.editor.request_close();
    CHECK(e.editor.may_close());
    e.editor.shutdown_graphics();
  }
  {  // Edited: asked, in a modal; Cancel keeps editing; Save writes the session's file, then closes.
    mostyle::test::OffscreenEditor e({1280, 720});
    Editor& ed = e.editor;
    edit_alpha(e, 0.9);
    ed.request_close();
    CHECK_FALSE(ed.may_close());
    CHECK(ed.asking_unsaved());
    for (int i = 0; i < 3; ++i) e.frame();
    const ImGuiWindow* modal = ImGui::FindWindowByName("Unsaved edits");
    REQUIRE(modal != nullptr);
    CHECK(modal->Active);
    ed.answer_unsaved(mostyle::ui::UnsavedQuestion::Answer::kCancel);
    for (int i = 0; i < 3; ++i) e.frame();
    CHECK_FALSE(ed.may_close());
    CHECK_FALSE(ImGui::FindWindowByName("Unsaved edits")->Active);
    const std::string path = scratch.path("kept.mostyle");
    REQUIRE(ed.save_session(path));
    ed.request_close();  // saved: nothing unsaved
    CHECK(ed.may_close());
    ed.shutdown_graphics();
  }
  {  // Edited after a save: Save writes it to the session's file and closes.
    mostyle::test::OffscreenEditor e({640, 360});
    Editor& ed = e.editor;
    edit_alpha(e, -1.0);
    const std::string path = scratch.path("again.mostyle");
    REQUIRE(ed.save_session(path));
    set_pair_alpha(ed.state().document, 0.1);
    ed.state().command_edits++;
    for (int i = 0; i < 3; ++i) e.frame();
    ed.request_close();
    REQUIRE(ed.asking_unsaved());
    ed.answer_unsaved(mostyle::ui::UnsavedQuestion::Answer::kSave);
    CHECK(ed.may_close());
    CHECK(mostyle::ui::pair_alpha(mostyle::ui::read_session_file(path).document) == 0.1);
    ed.shutdown_graphics();
  }
  {  // Discard closes without writing.
    mostyle::test::OffscreenEditor e({640, 360});
    edit_alpha(e, 0.3);
    e.editor.request_close();
    REQUIRE(e.editor.asking_unsaved());
    e.editor.answer_unsaved(mostyle::ui::UnsavedQuestion::Answer::kDiscard);
    CHECK(e.editor.may_close());
    e.editor.shutdown_graphics();
  }
}

TEST_CASE("opening a session over unsaved edits asks first; undo never ties a session to other takes") {
  namespace ui = mostyle::ui;
  ScratchDir scratch("mostyle_editor_open_over");
  const std::string happy = mostyle::test::asset("motions/cmu142_walk_happy.bvh");
  const std::string marching = mostyle::test::asset("motions/cmu142_walk_marching.bvh");
  const std::string joy = mostyle::test::asset("motions/cmu142_walk_joy.bvh");
  // The session on disk: joy and marching at alpha 0.2.
  const std::string bowday = scratch.path("bowday.mostyle");
  ui::SessionFile file;
  file.document.files = {joy, marching};
  file.document.parameters.components = 4;
  ui::set_pair_alpha(file.document, 0.2);
  ui::write_session_file(bowday, file);
  const ui::SessionFile on_disk = ui::read_session_file(bowday);

  mostyle::test::OffscreenEditor e({1280, 720});
  REQUIRE(e.gl.ok());
  Editor& ed = e.editor;
  edit_alpha(e, 0.9);  // unsaved work on the bundled pair
  REQUIRE(ed.edits().unsaved());
  // Opening asks first; Cancel keeps the work and opens nothing.
  ed.request_open(bowday);
  CHECK(ed.asking_unsaved());
  for (int i = 0; i < 3; ++i) e.frame();
  const ImGuiWindow* modal = ImGui::FindWindowByName("Unsaved edits");
  REQUIRE(modal != nullptr);
  CHECK(modal->Active);
  ed.answer_unsaved(ui::UnsavedQuestion::Answer::kCancel);
  for (int i = 0; i < 3; ++i) e.frame();
  CHECK(ed.session_path().empty());
  CHECK(ui::pair_alpha(ed.state().document) == Approx(0.9));
  // Discard opens it.
  ed.request_open(bowday);
  REQUIRE(ed.asking_unsaved());
  ed.answer_unsaved(ui::UnsavedQuestion::Answer::kDiscard);
  CHECK(ed.session_path() == fs::absolute(bowday).lexically_normal().string());
  ed.wait_for_engine();
  for (int i = 0; i < 3; ++i) e.frame();
  CHECK(ed.engine().snapshot().paths[0] == joy);
  // Ctrl+Z cannot bring the old takes back under this session's name: the open began anew.
  CHECK_FALSE(ed.edits().can_undo());
  CHECK_FALSE(ed.undo());
  CHECK(ed.engine().snapshot().paths[0] == joy);
  CHECK_FALSE(ed.edits().unsaved());
  // Closing now asks nothing, and the session file still holds its own takes.
  ed.request_close();
  CHECK(ed.may_close());
  CHECK(ui::read_session_file(bowday).document == on_disk.document);
  ed.shutdown_graphics();
}

namespace {

// A stand-in for Axis Neuron in this process: serves `clip`'s frames as BVH broadcasting lines
// to the first client that connects, all at once, then closes (app/live/tcp.h's calls).
struct LoopbackSource {
  int listener = -1, port = 0;
  std::thread thread;

  explicit LoopbackSource(const mostyle::Clip& clip) {
    listener = mostyle::live::listen_on({"127.0.0.1", 0}, &port);
    std::string lines;
    for (int f = 0; f < clip.frames(); ++f)
      mostyle::append_axis_line(&lines, 0, "Avatar00", nullptr, 0, clip.motion.row(f).data(), clip.skeleton.channel_count);
    thread = std::thread([this, lines] {
      pollfd p{listener, POLLIN, 0};
      if (::poll(&p, 1, 120000) != 1) return;
      const int client = ::accept4(listener, nullptr, nullptr, SOCK_CLOEXEC);
      if (client < 0) return;
      for (size_t sent = 0; sent < lines.size();) {
        const ssize_t n = ::send(client, lines.data() + sent, lines.size() - sent, MSG_NOSIGNAL);
        if (n <= 0) break;
        sent += static_cast<size_t>(n);
      }
      ::close(client);
    });
  }
  ~LoopbackSource() {
    thread.join();
    ::close(listener);
  }
};

// The same, sending the first `first` frames at once, then the rest once `release` is set, then
// closing: a connection that stays open while the test changes the takes.
struct HeldLoopbackSource {
  int listener = -1, port = 0;
  std::promise<void> release;
  std::thread thread;

  HeldLoopbackSource(const mostyle::Clip& clip, int first) {
    listener = mostyle::live::listen_on({"127.0.0.1", 0}, &port);
    std::string head, tail;
    for (int f = 0; f < clip.frames(); ++f)
      mostyle::append_axis_line(f < first ? &head : &tail, 0, "Avatar00", nullptr, 0, clip.motion.row(f).data(),
                                clip.skeleton.channel_count);
    std::shared_future<void> released = release.get_future().share();
    thread = std::thread([this, head, tail, released] {
      pollfd p{listener, POLLIN, 0};
      if (::poll(&p, 1, 120000) != 1) return;
      const int client = ::accept4(listener, nullptr, nullptr, SOCK_CLOEXEC);
      if (client < 0) return;
      auto send_all = [client](const std::string& lines) {
        for (size_t sent = 0; sent < lines.size();) {
          const ssize_t n = ::send(client, lines.data() + sent, lines.size() - sent, MSG_NOSIGNAL);
          if (n <= 0) return;
          sent += static_cast<size_t>(n);
        }
      };
      send_all(head);
      released.wait_for(std::chrono::seconds(120));
      send_all(tail);
      ::close(client);
    });
  }
  ~HeldLoopbackSource() {
    thread.join();
    ::close(listener);
  }
};

}  // namespace

TEST_CASE("editor options: --live and --live-skeleton go together") {
  const ParseResult both = parse({"--live", "localhost:7001", "--live-skeleton", "axis.bvh"});
  REQUIRE(both.status == ParseStatus::kRun);
  CHECK(both.options.live_address == "localhost:7001");
  CHECK(both.options.live_skeleton == "axis.bvh");
  const ParseResult alone = parse({"--live", "localhost:7001"});
  CHECK(alone.status == ParseStatus::kUsageError);
  CHECK_THAT(alone.error, Catch::Contains("--live-skeleton"));
}

TEST_CASE("editor: the Live source connects over loopback and shows the stream and the styled stream") {
  namespace ui = mostyle::ui;
  const std::string stream_file = mostyle::test::asset("motions/cmu142_walk_clumsy.bvh");
  const mostyle::Clip stream = mostyle::read_bvh_file(stream_file);
  LoopbackSource source(stream);
  mostyle::test::OffscreenEditor e({960, 540});
  REQUIRE(e.gl.ok());
  Editor& editor = e.editor;
  editor.wait_for_engine();
  editor.init_graphics();
  REQUIRE(editor.state().shown.size() == 3);  // the bundled pair and its blend
  const std::string blend_label = editor.state().shown[2].label;

  // What Connect does: the address and skeleton as typed, the loaded takes as neutral and style.
  editor.live().settings().address = "localhost:" + std::to_string(source.port);
  editor.live().settings().skeleton = stream_file;
  REQUIRE(editor.connect_live());
  REQUIRE(editor.live().wait_until([](const ui::LiveStatus& s) { return s.state == ui::LiveState::kClosed ||
                                                                        s.state == ui::LiveState::kFailed; },
                                   std::chrono::seconds(120)));
  INFO(editor.live().status().error);
  CHECK(editor.live().status().state == ui::LiveState::kClosed);
  CHECK(editor.live().status().styled == stream.frames());
  CHECK(editor.live().status().skipped == 0);
  CHECK(editor.live().status().strengths == std::vector<double>{0.5});  // the pair's alpha
  e.frame();
  e.frame();

  // The stream and the styled stream in place of the pair, the last window of the stream.
  CHECK(editor.live_shown());
  const auto& takes = editor.state().shown;
  REQUIRE(takes.size() == 2);
  CHECK(takes[0].label.find("stream") != std::string::npos);
  CHECK(takes[1].label == "styled");
  CHECK(takes[0].frames() == std::min(stream.frames(), static_cast<int>(ui::kLiveWindowSeconds * stream.fps())));
  CHECK(takes[1].frames() == takes[0].frames());
  CHECK(ui::live_status_line(editor.live().status()).rfind("source closed", 0) == 0);

  // Disconnect: the pair and its blend come back as they were.
  editor.live().disconnect();
  e.frame();
  CHECK_FALSE(editor.live_shown());
  REQUIRE(editor.state().shown.size() == 3);
  CHECK(editor.state().shown[2].label == blend_label);
  editor.shutdown_graphics();
}

TEST_CASE("editor: takes loaded while the Live source streams restyle it on the same connection") {
  namespace ui = mostyle::ui;
  const std::string stream_file = mostyle::test::asset("motions/cmu142_walk_clumsy.bvh");
  const mostyle::Clip stream = mostyle::read_bvh_file(stream_file);
  HeldLoopbackSource source(stream, 300);
  mostyle::test::OffscreenEditor e({960, 540});
  REQUIRE(e.gl.ok());
  Editor& editor = e.editor;
  editor.wait_for_engine();
  editor.init_graphics();
  editor.live().settings().address = "localhost:" + std::to_string(source.port);
  editor.live().settings().skeleton = stream_file;
  REQUIRE(editor.connect_live());
  REQUIRE(editor.live().wait_until([](const ui::LiveStatus& s) { return s.styled >= 300 || s.state == ui::LiveState::kFailed; },
                                   std::chrono::seconds(120)));
  CHECK(editor.live().status().strengths == std::vector<double>{0.5});  // the pair's alpha

  // A third take, as loading it in the Files panel does: a mix of three, the stream still open.
  load_walks(editor, {"cmu142_walk_happy", "cmu142_walk_marching", "cmu142_walk_joy"});
  CHECK(editor.live().status().state == ui::LiveState::kStreaming);
  CHECK(editor.live().status().restyling);
  const std::vector<double> mix = ui::live_strengths(editor.state().document, 3);
  REQUIRE(mix.size() == 2);

  // The rest of the stream on the same connection, styled with the three takes once they are made.
  REQUIRE(editor.live().wait_until([](const ui::LiveStatus& st) { return !st.restyling; }, std::chrono::seconds(120)));
  CHECK(editor.live().status().state == ui::LiveState::kStreaming);
  source.release.set_value();
  REQUIRE(editor.live().wait_until([](const ui::LiveStatus& s) { return s.state == ui::LiveState::kClosed ||
                                                                        s.state == ui::LiveState::kFailed; },
                                   std::chrono::seconds(120)));
  INFO(editor.live().status().error);
  const ui::LiveStatus& s = editor.live().status();
  CHECK(s.state == ui::LiveState::kClosed);
  CHECK(s.styled == stream.frames());  // every frame, one connection
  CHECK(s.restyle_error.empty());
  CHECK_FALSE(s.restyling);
  CHECK(s.strengths == mix);
  editor.live().disconnect();
  e.frame();
  editor.shutdown_graphics();
}

TEST_CASE("editor: at 1280x720 the Files panel's Live section shows whole at its foot, closed and open") {
  namespace ui = mostyle::ui;
  mostyle::test::OffscreenEditor e({1280, 720});
  REQUIRE(e.gl.ok());
  Editor& editor = e.editor;
  editor.wait_for_engine();
  editor.init_graphics();
  // The Files panel and its Live section (a child window of it, "Files/##live_<id>").
  auto live_in_view = [&e](float at_least) {
    e.frame();
    e.frame();
    const ImGuiWindow* files = ImGui::FindWindowByName(ui::panel_title(ui::PanelId::kFiles));
    REQUIRE(files != nullptr);
    const ImGuiWindow* live = nullptr;
    for (const ImGuiWindow* w : GImGui->Windows)
      if (w->ParentWindow == files && std::strstr(w->Name, "/##live_") != nullptr) live = w;
    REQUIRE(live != nullptr);
    CHECK(live->Active);
    CHECK(live->Pos.y >= files->InnerClipRect.Min.y - 0.5f);
    CHECK(live->Pos.y + live->Size.y <= files->InnerClipRect.Max.y + 0.5f);  // no part of it below the fold
    CHECK(live->Size.y >= at_least);
    CHECK(files->ScrollMax.y == 0.0f);  // the panel itself does not scroll: its body does
  };
  live_in_view(ImGui::GetFrameHeight());  // the pair: its header
  load_walks(editor, {"cmu142_walk_happy", "cmu142_walk_marching", "cmu142_walk_joy", "cmu142_walk_clumsy"});
  live_in_view(ImGui::GetFrameHeight());  // four take fields above it: still in view
  // Connected (here to a port nobody serves): the section opens, its fields, status and
  // recording rows in view.
  int port = 0;
  ::close(mostyle::live::listen_on({"127.0.0.1", 0}, &port));
  editor.live().settings().address = "127.0.0.1:" + std::to_string(port);
  editor.live().settings().skeleton = mostyle::test::asset("motions/cmu142_walk_clumsy.bvh");
  REQUIRE(editor.connect_live());
  REQUIRE(editor.live().wait_until([](const ui::LiveStatus& s) { return s.state == ui::LiveState::kFailed; },
                                   std::chrono::seconds(120)));
  live_in_view(5.0f * ImGui::GetFrameHeight());
  editor.shutdown_graphics();
}

TEST_CASE("editor: a Live address nobody serves, or that is not one, is said in one sentence") {
  namespace ui = mostyle::ui;
  int port = 0;
  ::close(mostyle::live::listen_on({"127.0.0.1", 0}, &port));  // a port just freed: nothing listens there
  Editor editor(mostyle::test::paused_small_pair());
  editor.wait_for_engine();
  editor.live().settings().address = "localhost:" + std::to_string(port);
  editor.live().settings().skeleton = mostyle::test::asset("motions/cmu142_walk_clumsy.bvh");
  REQUIRE(editor.connect_live());
  REQUIRE(editor.live().wait_until([](const ui::LiveStatus& s) { return s.state == ui::LiveState::kFailed; },
                                   std::chrono::seconds(120)));
  CHECK_THAT(editor.live().status().error, Catch::StartsWith("cannot connect to localhost:" + std::to_string(port)));
  editor.update_engine();
  CHECK_FALSE(editor.live_shown());
  CHECK(editor.state().shown.size() == 3);

  editor.live().settings().address = "localhost";
  REQUIRE(editor.connect_live());
  CHECK(editor.live().status().state == ui::LiveState::kFailed);
  CHECK_THAT(ui::live_status_line(editor.live().status()), Catch::StartsWith("Live address: expected HOST:PORT"));
}
