// The DTW panel's matched frames (ui/panels/dtw_panel.h) as each take's file counts them: a short
// B at 30 fps registered by cycles onto a longer A at 120 fps.
#include "ui/panels/dtw_panel.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "tests/test_data.h"

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

TEST_CASE("DTW panel: the matched frames are each take's own, counted at its file's rate") {
  const fs::path dir = fs::temp_directory_path() / ("mostyle_dtw_panel_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const int b_frames = 100;
  const std::string b = short_take_at_30(dir, b_frames);
  EditorState state;
  state.document.parameters.components = 4;
  BlendSession session;
  session.load(test::asset("motions/cmu142_walk_happy.bvh"), b);
  session.wait_idle(state);
  fs::remove_all(dir);
  INFO(session.error());
  const PreparedTakes* p = session.pair();
  REQUIRE(p != nullptr);
  const Alignment& al = p->takes[1].alignment;
  REQUIRE(al.by_cycles());
  REQUIRE(p->fps == 30.0);
  REQUIRE(p->takes[0].clip->fps() == Approx(120.0));
  // The registered B repeats B's cycles along A: its frames run past B's own.
  CHECK(al.b_last > b_frames - 1);

  const MatchedFrames m = matched_frames_in_files(*p);
  CHECK(m.a_first == std::lround(al.a_first * 4.0));  // A's file counts four frames to a working one
  CHECK(m.a_last == std::lround(al.a_last * 4.0));
  CHECK(m.a_last <= 1079);
  CHECK(0 <= m.b_first);
  CHECK(m.b_first < m.b_last);
  CHECK(m.b_last <= b_frames - 1);
  // Every own frame of B the registered frames in the matched range come from lies in B's range.
  int outside = 0;
  for (int k = al.b_first; k <= al.b_last; ++k)
    if (!std::isnan(al.b_source[k])) outside += std::lround(al.b_source[k]) < m.b_first || std::lround(al.b_source[k]) > m.b_last;
  CHECK(outside == 0);
}

TEST_CASE("DTW panel: each take's rests and actions as the before plot shades them") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  EditorState state;
  state.document.parameters.components = 4;
  BlendSession session;
  // A good-bye (an action between rests) and a wave (strokes of the left hand), aligned by their
  // structure: both plotted on their own frames.
  session.load(test::shared_motion("actions/bandai_bye_normal.bvh"),
               test::shared_motion("actions/bandai2_wave-left-hand_active.bvh"));
  session.wait_idle(state);
  INFO(session.error());
  const PreparedTakes* p = session.pair();
  REQUIRE(p != nullptr);
  for (int i = 0; i < 2; ++i) {
    const PreparedTake& t = p->takes[static_cast<size_t>(i)];
    const ActionSpans& s = t.cycles.spans;
    const StructureMarks m = structure_marks(t);
    const int frames = static_cast<int>(t.canonical.local.rows());
    INFO("take " << i << ": " << frames << " frames, rests " << s.rest_before << " and " << s.rest_after);
    REQUIRE(t.registration.empty());
    // Every frame is a rest or inside the moving span, the actions in order, none overlapping.
    int covered = 0, last = 0;
    for (const FrameSpan& r : m.rests) covered += r.frames();
    CHECK(m.actions.size() == s.actions.size());
    for (const FrameSpan& a : m.actions) {
      CHECK(a.begin >= last);
      CHECK(a.end <= frames);
      last = a.end;
    }
    CHECK(covered == s.rest_before + s.rest_after);
    if (!m.actions.empty()) CHECK(covered + (m.actions.back().end - m.actions.front().begin) <= frames);
  }
  // A walk registered by cycles onto another is plotted as registered: no marks of its own.
  BlendSession walks;
  walks.load(test::asset("motions/cmu142_walk_happy.bvh"), test::asset("motions/cmu142_walk_marching.bvh"));
  walks.wait_idle(state);
  REQUIRE(walks.pair() != nullptr);
  REQUIRE_FALSE(walks.pair()->takes[1].registration.empty());
  const StructureMarks none = structure_marks(walks.pair()->takes[1]);
  CHECK(none.rests.empty());
  CHECK(none.actions.empty());
}
