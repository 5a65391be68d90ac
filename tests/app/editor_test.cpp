// The editor shell: its command line, loading takes without a GL context, and the two
// programs end to end (offscreen screenshot; no display without --offscreen).
#include "app/editor.h"
#include "app/editor_options.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

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

TEST_CASE("the editor keeps a load error as the take's, and puts good takes on the floor") {
  EditorOptions options;
  options.files = {mostyle::test::asset("motions/cmu142_walk_happy.bvh"), "/nonexistent/walk.bvh",
                   mostyle::test::asset("motions/cmu142_walk_marching.bvh")};
  Editor editor(options);  // no GL context needed
  const auto& takes = editor.state().takes;
  REQUIRE(takes.size() == 3);
  CHECK(takes[0].ok());
  CHECK_FALSE(takes[1].ok());
  CHECK_THAT(takes[1].error, Catch::Contains("/nonexistent/walk.bvh"));
  CHECK(takes[2].ok());
  for (const auto* t : {&takes[0], &takes[2]}) {
    double lowest = 1e30;
    for (Eigen::Index j = 0; 3 * j < t->positions.cols(); ++j) lowest = std::min(lowest, t->positions.col(3 * j + 1).minCoeff());
    CHECK(lowest == Approx(0.0).margin(1e-9));
    CHECK(t->size > 10.0f);  // CMU units: about 30 tall
  }
  CHECK(editor.state().reference_take() == &takes[0]);
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
