// Where each cycle of the result came from (ui/model/cycle_provenance.h): a case worked by hand
// (a reference at 120 Hz in its file, a short take registered by cycles and reused, a take aligned
// whole whose cycles straddle the reference's), the span under a frame, the tooltip's words; and
// the bundled takes through the editor's two paths (a pair, a palette): the spans cover the
// result, a take registered by cycles shows in each output cycle the cycle the registration
// paired with the reference's, frame by frame, and a cycle shown again is said to be reused.
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "engine/align/prepare_takes.h"
#include "tests/test_data.h"
#include "tests/ui/loaded_takes.h"
#include "ui/model/cycle_provenance.h"

using namespace mostyle;
using namespace mostyle::ui;
using test::LoadedTakes;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Output frames next to a span's ends where a take's frame may be a neighbour cycle's: the
// alignment is smoothed across seams (alignment.h align_by_cycles), and a registered frame is
// rounded to the nearest (cycles_shown). The bundled takes need 2.
constexpr int kSeamFrames = 2;

TakeCycles cycles_of(std::vector<Cycle> cycles) {
  TakeCycles c;
  c.kind = CycleKind::kGait;
  c.cycles = std::move(cycles);
  return c;
}

// Three takes at 30 Hz over 12 output frames (sources: the reference's frame k at output frame
// k, the registered take's too, the third's k + 0.5):
//   A, the reference, a 120 Hz file (4 file frames per working frame): cycles [2,6) and [6,10);
//   B, registered by cycles with its one cycle [5,9) laid on both of A's (reused), its posture
//     only outside them;
//   C, aligned whole, cycles [0,5) and [5,9): it shows 0.5 .. 11.5.
PreparedTakes hand_takes() {
  PreparedTakes p;
  p.fps = 30.0;
  p.takes.resize(3);
  auto file = std::make_shared<Clip>();
  file->frame_time = 1.0 / 120.0;
  p.takes[0].clip = file;
  p.takes[0].cycles = cycles_of({{2, 6}, {6, 10}});
  CycleRegistration& r = p.takes[1].registration;
  r.take_cycles = cycles_of({{5, 9}});
  r.pairs = {0, 0};
  r.cycles = cycles_of({{2, 6}, {6, 10}});
  r.source.resize(12);
  r.source << kNaN, kNaN, 5, 6, 7, 8, 5, 6, 7, 8, kNaN, kNaN;
  r.source_cycle.resize(12);
  r.source_cycle << -1, -1, 0, 0, 0, 0, 0, 0, 0, 0, -1, -1;
  p.takes[1].cycles = r.take_cycles;
  p.takes[2].cycles = cycles_of({{0, 5}, {5, 9}});
  return p;
}

Eigen::MatrixXd hand_sources() {
  Eigen::MatrixXd s(12, 3);
  for (int k = 0; k < 12; ++k) s.row(k) << k, k, k + 0.5;
  return s;
}

void check_source(const TakeCycleSource& s, CycleSourceKind kind, int cycle, int first, int last, bool reused) {
  CHECK(s.kind == kind);
  CHECK(s.cycle == cycle);
  if (kind != CycleSourceKind::kPostureOnly) {
    CHECK(s.first_frame == first);
    CHECK(s.last_frame == last);
  }
  CHECK(s.reused == reused);
}

// The invariants of the spans of a real result: they cover its K frames in order; output cycles
// are numbered in order; each take's cycle is one it has, reused exactly when an earlier span
// showed it; a take registered by cycles shows, in each output cycle, the cycle paired with the
// reference's there, at every frame of it but the few next to a seam.
void check_real(const PreparedTakes& p, const Eigen::MatrixXd& sources, const std::vector<CycleProvenance>& spans) {
  REQUIRE_FALSE(spans.empty());
  CHECK(spans.front().begin == 0);
  CHECK(spans.back().end == sources.rows());
  int next_cycle = 0;
  std::vector<std::set<int>> seen(static_cast<size_t>(p.size()));
  int registered_cycles = 0, reused = 0;
  for (size_t s = 0; s < spans.size(); ++s) {
    const CycleProvenance& span = spans[s];
    CHECK(span.begin < span.end);
    if (s > 0) CHECK(span.begin == spans[s - 1].end);
    if (span.cycle >= 0) CHECK(span.cycle == next_cycle++);
    REQUIRE(static_cast<int>(span.takes.size()) == p.size());
    CHECK((span.cycle >= 0) == (span.takes[0].kind == CycleSourceKind::kCycle));
    for (int i = 0; i < p.size(); ++i) {
      const PreparedTake& take = p.takes[static_cast<size_t>(i)];
      const TakeCycleSource& from = span.takes[static_cast<size_t>(i)];
      if (from.kind != CycleSourceKind::kCycle) continue;
      const TakeCycles& own = take.registration.empty() ? take.cycles : take.registration.take_cycles;
      REQUIRE(from.cycle >= 0);
      REQUIRE(from.cycle < static_cast<int>(own.cycles.size()));
      CHECK(from.first_frame <= from.last_frame);
      CHECK(from.begin_s < from.end_s);
      CHECK(from.reused == !seen[static_cast<size_t>(i)].insert(from.cycle).second);
      reused += from.reused ? 1 : 0;
      if (take.registration.empty() || span.cycle < 0) continue;
      // Registered: the cycle paired with the reference's, at every output frame of the cycle
      // away from its seams.
      ++registered_cycles;
      CHECK(from.cycle == take.registration.pairs[static_cast<size_t>(span.slot)]);
      const Eigen::VectorXi shown = cycles_shown(take, sources.col(i));
      for (int k = span.begin + kSeamFrames; k < span.end - kSeamFrames; ++k) CHECK(shown[k] == from.cycle);
    }
  }
  CHECK(next_cycle > 0);
  CHECK(registered_cycles > 0);  // the bundled walks are registered by cycles
  INFO("take cycles reused: " << reused);
}

}  // namespace

TEST_CASE("cycle provenance: a case worked by hand") {
  const PreparedTakes p = hand_takes();
  const std::vector<CycleProvenance> spans = cycle_provenance(p, hand_sources(), {"A", "B", "C"});
  REQUIRE(spans.size() == 4);
  // Before A's first cycle, its two cycles, after its last.
  const int bounds[5] = {0, 2, 6, 10, 12};
  const int cycle[4] = {-1, 0, 1, -1};
  for (size_t s = 0; s < 4; ++s) {
    CHECK(spans[s].begin == bounds[s]);
    CHECK(spans[s].end == bounds[s + 1]);
    CHECK(spans[s].cycle == cycle[s]);
    REQUIRE(spans[s].takes.size() == 3);
    CHECK(spans[s].takes[0].take == "A");
    CHECK(spans[s].takes[2].take == "C");
  }
  using K = CycleSourceKind;
  // A: its own frames 0-1, [2,6), [6,10), 10-11 at 30 Hz, four times those in its file.
  check_source(spans[0].takes[0], K::kOutsideCycles, -1, 0, 4, false);
  check_source(spans[1].takes[0], K::kCycle, 0, 8, 23, false);
  check_source(spans[2].takes[0], K::kCycle, 1, 24, 39, false);
  check_source(spans[3].takes[0], K::kOutsideCycles, -1, 40, 44, false);
  CHECK(spans[1].takes[0].begin_s == Approx(2.0 / 30.0));
  CHECK(spans[1].takes[0].end_s == Approx(6.0 / 30.0));
  // B: its posture only outside A's cycles; its one cycle in both, the second time reused.
  check_source(spans[0].takes[1], K::kPostureOnly, -1, 0, 0, false);
  check_source(spans[1].takes[1], K::kCycle, 0, 5, 8, false);
  check_source(spans[2].takes[1], K::kCycle, 0, 5, 8, true);
  check_source(spans[3].takes[1], K::kPostureOnly, -1, 0, 0, false);
  // C, half a frame on: its cycle 0 at most of [0,2) and [2,6) (3 of 4), its cycle 1 at 3 of
  // [6,10)'s 4, none at 10.5 and 11.5 (frames 11-12, rounded half away from zero).
  check_source(spans[0].takes[2], K::kCycle, 0, 0, 4, false);
  check_source(spans[1].takes[2], K::kCycle, 0, 0, 4, true);
  check_source(spans[2].takes[2], K::kCycle, 1, 5, 8, false);
  check_source(spans[3].takes[2], K::kOutsideCycles, -1, 11, 12, false);
  CHECK(spans[3].takes[2].begin_s == Approx(10.5 / 30.0));
  CHECK(spans[3].takes[2].end_s == Approx(11.5 / 30.0));

  SECTION("the span under a frame") {
    CHECK(provenance_at(spans, -1) == -1);
    CHECK(provenance_at(spans, 0) == 0);
    CHECK(provenance_at(spans, 1) == 0);
    CHECK(provenance_at(spans, 2) == 1);
    CHECK(provenance_at(spans, 9) == 2);
    CHECK(provenance_at(spans, 11) == 3);
    CHECK(provenance_at(spans, 12) == -1);
    CHECK(provenance_at({}, 0) == -1);
  }
  SECTION("the tooltip's words") {
    CHECK(provenance_text(spans[2], 30.0) ==
          "Cycle 2 of the result (0.20-0.33 s)\n"
          "A: cycle 2, frames 24-39 of its file (0.20-0.33 s)\n"
          "B: cycle 1, frames 5-8 of its file (0.17-0.30 s), reused\n"
          "C: cycle 2, frames 5-8 of its file (0.17-0.30 s)");
    CHECK(provenance_text(spans[0], 30.0) ==
          "Outside the reference's cycles (0.00-0.07 s)\n"
          "A: outside its cycles, frames 0-4 of its file (0.00-0.03 s)\n"
          "B: its posture only, on the reference's motion\n"
          "C: cycle 1, frames 0-4 of its file (0.00-0.17 s)");
  }
  SECTION("a name missing, no frames") {
    const std::vector<CycleProvenance> unnamed = cycle_provenance(p, hand_sources(), {"A"});
    CHECK(unnamed[0].takes[1].take == "take 2");
    CHECK(cycle_provenance(p, Eigen::MatrixXd(0, 3), {"A", "B", "C"}).empty());
  }
}

TEST_CASE("cycle provenance: a pair's blend in the editor, each output cycle from the paired take cycles") {
  LoadedTakes s;
  const PreparedTakes* p = s.engine.takes();
  REQUIRE(p != nullptr);
  REQUIRE(s.engine.result() != nullptr);
  const std::vector<CycleProvenance>& spans = s.state.cycle_provenance;
  CHECK(spans.back().end == s.state.reference_take()->frames());  // the timeline's frames
  check_real(*p, s.engine.result()->sources, spans);
  CHECK(spans.front().takes[1].take == "B");
  // A new alpha: a new blend, its spans made again (the timing may change its length).
  set_pair_alpha(s.state.document, 0.9);
  s.engine.sync(s.state);
  CHECK(s.state.cycle_provenance.back().end == s.engine.result()->sources.rows());
  check_real(*p, s.engine.result()->sources, s.state.cycle_provenance);
}

TEST_CASE("cycle provenance: a palette's mix in the editor, a short take's cycles reused") {
  LoadedTakes s;
  s.engine.load_files({test::asset("motions/cmu142_walk_happy.bvh"), test::asset("motions/cmu142_walk_marching.bvh"),
                        test::asset("motions/cmu142_walk_joy.bvh")});
  s.engine.wait_idle(s.state);
  const PreparedTakes* p = s.engine.takes();
  REQUIRE(p != nullptr);
  REQUIRE(s.engine.result_view().mix() != nullptr);
  const std::vector<CycleProvenance>& spans = s.state.cycle_provenance;
  check_real(*p, s.engine.result_view().mix()->sources, spans);
  CHECK(spans.front().takes[2].take == "cmu142_walk_joy");
  // A take registered with fewer cycles than the reference's shown in the result has one reused.
  for (int i = 1; i < p->size(); ++i) {
    const PreparedTake& take = p->takes[static_cast<size_t>(i)];
    int output_cycles = 0, reused = 0;
    for (const CycleProvenance& span : spans) {
      if (span.cycle < 0) continue;
      ++output_cycles;
      reused += span.takes[static_cast<size_t>(i)].reused ? 1 : 0;
    }
    const int own = static_cast<int>(take.registration.take_cycles.cycles.size());
    if (!take.registration.empty() && own < output_cycles) CHECK(reused >= output_cycles - own);
  }
}
