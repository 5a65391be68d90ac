// The alignment view's matched frames (ui/panels/alignment_view.h) as each take's file counts them: a short
// B at 30 fps registered by cycles onto a longer A at 120 fps.
#include "ui/panels/alignment_view.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "tests/test_data.h"
#include "tests/ui/loaded_takes.h"

using namespace mostyle;
using namespace mostyle::ui;
namespace fs = std::filesystem;

namespace {

// The bundled marching walk (120 fps) as a BVH of `frames` frames at 30 fps: every fourth frame.
std::string short_take_at_30(const fs::path& dir, int frames) {
  std::ifstream in(test::asset("motions/cmu142_walk_marching.bvh"));
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line) && line.rfind("MOTION", 0) != 0) out << line << '\n';
  out << "MOTION\nFrames: " << frames << "\nFrame Time: 0.0333333\n";
  std::getline(in, line);  // Frames:
  std::getline(in, line);  // Frame Time:
  for (int k = 0, kept = 0; kept < frames && std::getline(in, line); ++k)
    if (k % 4 == 0) {
      out << line << '\n';
      ++kept;
    }
  const std::string path = (dir / "marching_short_30.bvh").string();
  std::ofstream(path) << out.str();
  return path;
}

}  // namespace

TEST_CASE("alignment view: the matched frames are each take's own, counted at its file's rate") {
  const fs::path dir = fs::temp_directory_path() / ("mostyle_alignment_view_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const int b_frames = 100;
  const test::LoadedTakes s(test::asset("motions/cmu142_walk_happy.bvh"), short_take_at_30(dir, b_frames));
  const EngineLink& engine = s.engine;
  fs::remove_all(dir);
  INFO(engine.error());
  const PreparedTakes* p = engine.takes();
  REQUIRE(p != nullptr);
  const Alignment& al = p->takes[1].alignment;
  REQUIRE(al.by_cycles());
  REQUIRE(p->fps == 30.0);
  REQUIRE(p->takes[0].clip->fps() == Approx(120.0));
  // The registered B repeats B's cycles along A: its frames run past B's own.
  CHECK(al.b_last > b_frames - 1);

  const MatchedFrames m = matched_frames_in_files(*p, 1);
  CHECK(m.reference_first == std::lround(al.a_first * 4.0));  // A's file counts four frames to a working one
  CHECK(m.reference_last == std::lround(al.a_last * 4.0));
  CHECK(m.reference_last <= 1079);
  CHECK(0 <= m.take_first);
  CHECK(m.take_first < m.take_last);
  CHECK(m.take_last <= b_frames - 1);
  // Every own frame of B the registered frames in the matched range come from lies in B's range.
  int outside = 0;
  for (int k = al.b_first; k <= al.b_last; ++k)
    if (!std::isnan(al.b_source[k]))
      outside += std::lround(al.b_source[k]) < m.take_first || std::lround(al.b_source[k]) > m.take_last;
  CHECK(outside == 0);
  // The reference has no alignment of its own, and a take that is not there none either.
  CHECK(matched_frames_in_files(*p, 0).take_last == 0);
  CHECK(matched_frames_in_files(*p, 2).take_last == 0);
  CHECK_FALSE(alignment_plottable(*p, 0));
  CHECK(alignment_plottable(*p, 1));
}
