// A take's structure as the takes' views shade it (ui/model/take_structure.h), on a take made by
// hand: rest, an action holding two gait cycles, a pause, a second action, rest; a take
// registered by cycles, whose timeline's frames go back to its own (NaN: its posture only); and
// the spans the views shade on a good-bye, a wave and a registered walk.
#include <cmath>

#include <catch2/catch.hpp>

#include "tests/test_data.h"
#include "tests/ui/loaded_takes.h"
#include "ui/model/take_structure.h"

using namespace mostyle;
using namespace mostyle::ui;

namespace {

// 100 frames: rest [0, 10), action [10, 50) with cycles [12, 30) and [30, 48), a pause,
// action [60, 80), rest [80, 100).
PreparedTake hand_made() {
  PreparedTake t;
  t.cycles.kind = CycleKind::kGait;
  t.cycles.cycles = {Cycle{12, 30}, Cycle{30, 48}};
  ActionSpans& s = t.cycles.spans;
  s.frames = 100;
  s.rest_before = 10;
  s.rest_after = 20;
  s.actions = {FrameSpan{10, 50}, FrameSpan{60, 80}};
  return t;
}

}  // namespace

TEST_CASE("take structure: rests, actions and cycles by frame, in words") {
  const PreparedTake t = hand_made();
  CHECK(frame_structure(t, 5) == FrameStructure{FramePart::kRest, -1});
  CHECK(frame_structure(t, 11) == FrameStructure{FramePart::kAction, 0});
  CHECK(frame_structure(t, 12) == FrameStructure{FramePart::kCycle, 0});
  CHECK(frame_structure(t, 29.9) == FrameStructure{FramePart::kCycle, 0});
  CHECK(frame_structure(t, 30) == FrameStructure{FramePart::kCycle, 1});
  CHECK(frame_structure(t, 55) == FrameStructure{FramePart::kRest, -1});
  CHECK(frame_structure(t, 70) == FrameStructure{FramePart::kAction, 1});
  CHECK(frame_structure(t, NAN).part == FramePart::kPosture);
  CHECK(frame_structure_words(t, 5) == "at rest before the action");
  CHECK(frame_structure_words(t, 31) == "gait cycle 2 of 2");
  CHECK(frame_structure_words(t, 55) == "a pause between actions");
  CHECK(frame_structure_words(t, 70) == "action 2 of 2");
  CHECK(frame_structure_words(t, 90) == "at rest after the action");
  CHECK(frame_structure_words(t, NAN) == "its posture only");
}

TEST_CASE("take structure: a still take rests throughout, a periodic one's cycles are strokes") {
  PreparedTake still;
  still.cycles.spans.frames = still.cycles.spans.rest_before = 40;
  CHECK(frame_structure_words(still, 20) == "at rest");
  PreparedTake waving = hand_made();
  waving.cycles.kind = CycleKind::kPeriodic;
  CHECK(frame_structure_words(waving, 13) == "stroke 1 of 2");
}

TEST_CASE("take structure: a take's own frame on its timeline, through its registration") {
  PreparedTake whole = hand_made();
  CHECK(own_frame(whole, 42) == 42.0);
  PreparedTake registered = hand_made();
  registered.registration.pairs = {0};
  registered.registration.source = Eigen::Vector4d(3.0, 4.0, NAN, 12.5);
  CHECK(own_frame(registered, 1) == 4.0);
  CHECK(std::isnan(own_frame(registered, 2)));
  CHECK(own_frame(registered, 9) == 12.5);  // past the end: the last
}

TEST_CASE("take structure: the spans of a good-bye and a wave tile their frames, rests and actions as read") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  // A good-bye (an action between rests) and a wave (strokes of the left hand), aligned by their
  // structure: both on their own frames.
  const test::LoadedTakes loaded(test::shared_motion("actions/bandai_bye_normal.bvh"),
                              test::shared_motion("actions/bandai2_wave-left-hand_active.bvh"));
  INFO(loaded.engine.error());
  const PreparedTakes* p = loaded.engine.takes();
  REQUIRE(p != nullptr);
  for (const PreparedTake& t : p->takes) {
    const ActionSpans& s = t.cycles.spans;
    const int frames = static_cast<int>(t.canonical.local.rows());
    INFO(t.clip->source << ": " << frames << " frames, rests " << s.rest_before << " and " << s.rest_after);
    REQUIRE(t.registration.empty());
    const std::vector<StructureSpan> spans = structure_spans(t, frames, [&](int f) { return own_frame(t, f); });
    REQUIRE_FALSE(spans.empty());
    int at = 0, moving = 0, in_actions = 0;
    for (const StructureSpan& r : spans) {
      CHECK(r.begin == at);  // in order, none overlapping, none missing
      at = r.end;
      if (r.structure.part != FramePart::kRest) moving += r.end - r.begin;
      CHECK(r.structure.part != FramePart::kPosture);
    }
    CHECK(at == frames);
    for (const FrameSpan& a : s.actions) in_actions += std::min(a.end, frames) - a.begin;
    CHECK(moving == in_actions);
    if (s.rest_before > 0) CHECK(spans.front().end == s.rest_before);
  }
}

TEST_CASE("take structure: a walk registered by cycles shows its own cycles again and again") {
  const test::LoadedTakes walks;  // the bundled pair
  REQUIRE(walks.engine.takes() != nullptr);
  const PreparedTake& t = walks.engine.takes()->takes[1];
  REQUIRE_FALSE(t.registration.empty());
  const int frames = static_cast<int>(t.registration.source.size());
  const std::vector<StructureSpan> spans = structure_spans(t, frames, [&](int f) { return own_frame(t, f); });
  int cycles = 0;
  for (const StructureSpan& r : spans) cycles += r.structure.part == FramePart::kCycle;
  // Each reference cycle shows one of the take's: at least as many cycle spans as it has.
  CHECK(cycles >= static_cast<int>(t.registration.cycles.cycles.size()));
}
