// The editor shell: its command line, loading takes without a GL context, and the two
// programs end to end (offscreen screenshot; no display without --offscreen).
#include "app/editor.h"
#include "app/editor_options.h"
#include "app/imgui_session.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <imgui.h>

#include "tests/render/osmesa_context.h"

#include "render/png_io.h"
#include "tests/test_data.h"

using namespace mostyle::app;
namespace fs = std::filesystem;

namespace {
ParseResult parse(std::vector<const char*> args) {
  args.insert(args.begin(), "mostyle");
  return parse_editor_options(static_cast<int>(args.size()), args.data());
}

// Runs a shell command; returns its exit status and (if asked) what it wrote on stderr.
int run(const std::string& command, std::string* stderr_text = nullptr) {
  const std::string err = (fs::temp_directory_path() / "mostyle_editor_test.err").string();
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
}  // namespace

TEST_CASE("editor options: files and flags, both spellings") {
  ParseResult r = parse({"a.bvh", "--alpha", "0.25", "--components=7", "--sparsity", "0.5", "--frame", "12",
                         "b.bvh", "--screenshot", "out.png"});
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.files == std::vector<std::string>{"a.bvh", "b.bvh"});
  CHECK(r.options.initial.parameters.alpha == 0.25);
  CHECK(r.options.initial.parameters.components == 7);
  CHECK(r.options.initial.parameters.sparsity == 0.5);
  CHECK(r.options.initial.frame == 12);
  CHECK(r.options.screenshot_path == "out.png");
  CHECK_FALSE(r.options.offscreen);
}

TEST_CASE("editor options: defaults are the paper's, and --help") {
  ParseResult r = parse({});
  REQUIRE(r.status == ParseStatus::kRun);
  CHECK(r.options.files.empty());
  CHECK(r.options.initial.parameters.alpha == 0.5);
  CHECK(r.options.initial.parameters.components == 10);
  CHECK(r.options.initial.parameters.sparsity == 0.1);
  CHECK(parse({"--help"}).status == ParseStatus::kHelp);
  CHECK(parse({"-h"}).status == ParseStatus::kHelp);
  CHECK_THAT(editor_usage(), Catch::Contains("--offscreen") && Catch::Contains("--screenshot"));
}

TEST_CASE("editor options: bad values and unknown flags are usage errors that say which") {
  struct Case {
    std::vector<const char*> args;
    const char* mentions;
  };
  const std::vector<Case> cases = {
      {{"--alpha", "1.5"}, "--alpha"},      {{"--alpha", "x"}, "--alpha"},
      {{"--alpha"}, "--alpha"},             {{"--components", "0"}, "--components"},
      {{"--components", "2.5"}, "--components"}, {{"--sparsity", "0"}, "--sparsity"},
      {{"--frame", "-1"}, "--frame"},       {{"--screenshot"}, "--screenshot"},
      {{"--bogus"}, "--bogus"},             {{"-x"}, "-x"},
      {{"--offscreen"}, "--screenshot"},    {{"--offscreen=1", "--screenshot", "a.png"}, "--offscreen"},
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
  const auto& takes = editor.state().takes;
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

  editor.session().load("/nonexistent/walk.bvh", mostyle::test::asset("motions/cmu142_walk_marching.bvh"));
  editor.wait_for_engine();
  CHECK_THAT(editor.session().error(), Catch::Contains("/nonexistent/walk.bvh"));
  CHECK(editor.state().takes.size() == 3);
}

TEST_CASE("the editor keeps rendering offscreen for hundreds of frames while decompositions run") {
  const glm::ivec2 size(800, 450);
  mostyle::test::OsMesaContext gl(size);
  REQUIRE(gl.ok());
  ImGuiSession imgui(/*persist_layout=*/false);
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
    if (frame % 60 == 30 && !state.takes.empty()) {  // a new k or sparsity: re-decomposition
      state.parameters.components = 6 + 2 * ((frame / 60) % 4);
      state.parameters.sparsity = frame % 120 == 30 ? 0.2 : 0.3;
      editor.session().request_decomposition(state);
      ++decompositions_requested;
    }
    state.parameters.alpha = 0.5 + 0.5 * std::sin(frame * 0.1);  // blended in this very frame
    if (frame % 90 == 45) state.view.overlay = !state.view.overlay;
    editor.frame(FrameInput{size, 1.0f / 60.0f});
    // The frame went on while the decomposition it asked for was not there yet.
    if (editor.session().decomposition_outdated()) ++frames_while_busy;
    if (state.takes.size() == 3) {
      const Eigen::MatrixXd& blend = state.takes[2].positions;
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
  CHECK(editor.session().error().empty());
  const auto& shown = editor.session().snapshot().decompose_params;
  CHECK(shown.components == state.parameters.components);  // the last request won
  CHECK(shown.sparsity == state.parameters.sparsity);
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

TEST_CASE("mostyle without a display says so in one line and exits 1, --offscreen still works") {
  std::string err;
  CHECK(run(std::string("env -u DISPLAY -u WAYLAND_DISPLAY ") + MOSTYLE_EXE, &err) == 1);
  CHECK(err == "mostyle: no display; run under xvfb-run or pass --offscreen\n");
  const std::string out = (fs::temp_directory_path() / "mostyle_editor_test_exec.png").string();
  fs::remove(out);
  CHECK(run(std::string("env -u DISPLAY ") + MOSTYLE_EXE + " --offscreen --screenshot " + out, &err) == 0);
  CHECK(fs::exists(out));
  fs::remove(out);
  CHECK(run(std::string(MOSTYLE_EXE) + " --alpha 7", &err) == 2);
  CHECK(err == "mostyle: --alpha: expected a number in [0, 1], got '7'\n");
}
