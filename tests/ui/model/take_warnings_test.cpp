// Each warning under the take it speaks of (ui/model/take_warnings.h): by hand, and in the editor's
// takes for a pair whose B has a wrong frame count.
#include "ui/model/take_warnings.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "tests/ui/loaded_takes.h"

using namespace mostyle;
using namespace mostyle::ui;
namespace fs = std::filesystem;
using Lists = std::vector<std::vector<std::string>>;

TEST_CASE("take warnings: a reader's warning under the file it names, an alignment's under the take aligned") {
  const std::vector<std::string> paths = {"/data/a/walk.bvh", "/data/b/walk.bvh", "run.glb#sprint"};
  const std::vector<std::string> load = {"/data/b/walk.bvh:9: Frames: says 10 but the file has 8",
                                         "run.glb: read animation 'sprint'", "walk.bvh:3: a note by file name",
                                         "something else"};
  const Lists aligned = {{}, {"A's frames 1-9 match B's frames 2-8 poorly", "only A's frames 0-9 match the other take"},
                         {"only run.glb's frames 3-4 match walk.bvh"}};
  const std::vector<TakeMessages> got = warnings_by_take(paths, load, aligned, {"A", "B", "run.glb"});
  const std::vector<TakeMessages> want = {
      {{"walk.bvh:3: a note by file name", "something else"}, {"only A's frames 0-9 match the other take"}},
      {{"/data/b/walk.bvh:9: Frames: says 10 but the file has 8"}, {"A's frames 1-9 match B's frames 2-8 poorly"}},
      {{"run.glb: read animation 'sprint'"}, {"only run.glb's frames 3-4 match walk.bvh"}}};
  CHECK(got == want);
  CHECK(warnings_by_take({}, load, aligned, {}).empty());
}

TEST_CASE("take warnings: an alignment sentence given for several takes is said once, saying for how many") {
  const std::vector<std::string> paths = {"bye_normal.bvh", "bye_active.bvh", "bye_giant.bvh", "bye_musical.bvh"};
  const std::string same = "aligned whole, not by cycles: bye_normal has no cycles: no foot strike";
  const Lists aligned = {{}, {same}, {same, "its own"}, {same}};
  const std::vector<TakeMessages> got = warnings_by_take(paths, {}, aligned, {"bye_normal", "bye_active", "bye_giant", "bye_musical"});
  REQUIRE(got.size() == 4);
  CHECK(got[1].alignment == std::vector<std::string>{same + " (the same for 3 takes)"});
  CHECK(got[2].alignment == std::vector<std::string>{"its own"});
  CHECK(got[3].alignment.empty());
}

TEST_CASE("take warnings: a pair whose B says a wrong frame count shows the warning under B, not A") {
  const fs::path dir = fs::temp_directory_path() / ("mostyle_take_warnings_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ifstream in(test::asset("motions/cmu142_walk_marching.bvh"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = text.find("Frames: ");
  REQUIRE(at != std::string::npos);
  const size_t digits = text.find_first_not_of("0123456789", at + 8);
  text.replace(at + 8, digits - (at + 8), "100");  // fewer than the file has: loaded whole, with a warning
  const std::string b = (dir / "marching_cut.bvh").string();
  std::ofstream(b) << text;

  const test::LoadedTakes s(test::asset("motions/cmu142_walk_happy.bvh"), b);
  const EditorState& state = s.state;
  fs::remove_all(dir);
  REQUIRE(state.shown.size() == 3);
  REQUIRE(state.shown[1].ok());
  CAPTURE(state.shown[0].warnings, state.shown[1].warnings);
  bool on_b = false;
  for (const std::string& w : state.shown[1].warnings) on_b |= w.find("marching_cut.bvh:") != std::string::npos;
  CHECK(on_b);
  for (const std::string& w : state.shown[0].warnings) CHECK(w.find("marching_cut.bvh:") == std::string::npos);
}
