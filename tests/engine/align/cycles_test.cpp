// Cycles of a take (engine/align/cycles.h): strikes worked by hand; gait cycles of made-up
// stepping with pauses, uneven steps and flickering contacts; periods of a made-up wave with a
// still start, with a harmonic; none for a take that does not repeat; and the real walks of both
// conventions and frame rates.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "engine/align/cycles.h"
#include "engine/io/error.h"
#include "engine/io/motion_file.h"
#include "engine/run/prepare_takes.h"
#include "tests/test_data.h"

using namespace mostyle;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Contacts of a walk: five frames on the right foot, then cycles of `frames[k]` frames, the left
// foot planted for the first 60% of each, the right from 50% to 110% (into the next cycle); with
// `still` frames on both feet before cycle `pause_before` (a stop: the left foot stays down into
// that cycle). starts: where each cycle begins.
Eigen::MatrixXd stepping(const std::vector<int>& frames, int pause_before = -1, int still = 0,
                         std::vector<int>* starts = nullptr) {
  constexpr int kLeadIn = 5;
  int total = kLeadIn + still + 1;
  for (int f : frames) total += f;
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(total, 2);
  c.topRows(kLeadIn).col(1).setOnes();
  int at = kLeadIn;
  for (size_t k = 0; k < frames.size(); ++k) {
    if (static_cast<int>(k) == pause_before) {
      c.middleRows(at, still).setOnes();
      at += still;
    }
    if (starts != nullptr) starts->push_back(at);
    const int n = frames[k];
    for (int f = 0; f < n; ++f) {
      const double phase = double(f) / n;
      if (phase < 0.6) c(at + f, 0) = 1.0;
      if (phase >= 0.5 || phase < 0.1) c(at + f, 1) = 1.0;  // the right foot's stance runs into the next cycle
    }
    at += n;
  }
  c(at, 0) = 1.0;  // the last left strike closes the last cycle
  if (starts != nullptr) starts->push_back(at);
  return c;
}

Eigen::MatrixXd still_pose(Eigen::Index frames, int channels = 9) { return Eigen::MatrixXd::Zero(frames, channels); }

}  // namespace

TEST_CASE("cycles: foot strikes are landings, worked by hand") {
  Eigen::MatrixXd c(8, 2);
  c << 1, 0,  //
      1, 0,   //
      0, 1,   // right lands at 2
      0, 1,   //
      1, 0,   // left lands at 4
      1, 1,   // right lands at 5
      0, 0,   //
      1, 1;   // both land at 7
  CHECK(foot_strikes(c, 0) == std::vector<int>{4, 7});  // frame 0 planted is not a strike
  CHECK(foot_strikes(c, 1) == std::vector<int>{2, 5, 7});
}

TEST_CASE("cycles: where a take shown at other frames starts its cycles") {
  TakeCycles t;
  t.cycles = {{10, 40}, {40, 70}};
  Eigen::VectorXd shown(8);
  shown << 0, 9.5, 10.0, 25, 39.9, 41, 20, 45;  // slowed, sped up, then back (a cycle shown again)
  CHECK(cycle_starts_at(t, shown) == std::vector<int>{2, 5, 7});
  Eigen::VectorXd from_begin(2);
  from_begin << 10, 11;
  CHECK(cycle_starts_at(t, from_begin) == std::vector<int>{0});
  CHECK(cycle_starts_at(TakeCycles(), shown).empty());
}

TEST_CASE("cycles: gait cycles from left strike to left strike, each its own length, a stop left out") {
  const double fps = 30.0;
  const std::vector<int> lengths = {30, 32, 29, 31, 30, 33, 30, 28, 31, 30};
  std::vector<int> starts;
  const Eigen::MatrixXd contacts = stepping(lengths, /*pause_before=*/5, /*still=*/90, &starts);
  const TakeCycles t = detect_cycles(contacts, still_pose(contacts.rows()), fps, 1.0);
  CHECK(t.kind == CycleKind::kGait);
  CHECK(t.foot == 0);
  // Cycle 4 ends with the left foot landing into the 3 s stop; cycle 5 starts from it with the left
  // foot down (no strike), so from that landing to the next is no cycle: the nine others, each as
  // long as it was.
  std::vector<int> expected = {0, 1, 2, 3, 4, 6, 7, 8, 9};
  REQUIRE(t.cycles.size() == expected.size());
  int in_cycles = 0;
  for (size_t k = 0; k < expected.size(); ++k) {
    const size_t c = static_cast<size_t>(expected[k]);
    CHECK(t.cycles[k].begin == starts[c]);
    CHECK(t.cycles[k].frames() == lengths[c]);
    in_cycles += lengths[c];
  }
  CHECK(t.period == Approx(30.0).margin(1.0));
  CHECK(t.frames_in_cycles() == in_cycles);
}

TEST_CASE("cycles: a flickering contact, a shuffle and a lone foot do not make cycles of their own") {
  const double fps = 30.0;
  std::vector<int> starts;
  Eigen::MatrixXd contacts = stepping(std::vector<int>(6, 30), -1, 0, &starts);
  contacts(starts[1] + 8, 0) = 0.0;  // the left foot lifts for one frame mid-stance (a flicker)...
  contacts(starts[3] + 12, 0) = 0.0;  // ... twice
  const TakeCycles t = detect_cycles(contacts, still_pose(contacts.rows()), fps, 1.0);
  REQUIRE(t.kind == CycleKind::kGait);
  CHECK(t.cycles.size() == 6);
  for (const Cycle& c : t.cycles) CHECK(c.frames() == 30);
  // One foot only (hopping on it): no step of the other foot, no gait; still joints: no period.
  Eigen::MatrixXd hop = Eigen::MatrixXd::Zero(200, 2);
  for (int f = 0; f < 200; ++f) hop(f, 0) = (f % 25) < 12 ? 1.0 : 0.0;
  CHECK(detect_cycles(hop, still_pose(200), fps, 1.0).kind == CycleKind::kNone);
}

TEST_CASE("cycles: a wave repeats with its period, cut where the hand is lowest, its still start left out") {
  const double fps = 30.0, period_s = 0.8;
  const Eigen::Index frames = 300;
  Eigen::MatrixXd local = still_pose(frames);
  for (Eigen::Index f = 30; f < frames; ++f) {  // still for a second, then waving
    const double t = double(f) / fps;
    local(f, 4) = 0.3 * std::sin(2 * kPi * t / period_s);
    local(f, 5) = 0.1 * std::cos(2 * kPi * t / period_s);
  }
  const Eigen::MatrixXd planted = Eigen::MatrixXd::Ones(frames, 2);
  const TakeCycles t = detect_cycles(planted, local, fps, 1.0);
  REQUIRE(t.kind == CycleKind::kPeriodic);
  CHECK(t.period == Approx(period_s * fps).margin(1.0));
  REQUIRE(t.cycles.size() >= 9);
  CHECK(t.cycles.front().begin >= 24);  // not in the still second
  for (const Cycle& c : t.cycles) {
    CHECK(c.frames() == Approx(period_s * fps).margin(2.0));
    CHECK(local(c.begin, 4) < -0.25);  // at the bottom of the wave
  }
  // A strong second harmonic does not halve the period.
  Eigen::MatrixXd rich = still_pose(frames);
  for (Eigen::Index f = 0; f < frames; ++f) {
    const double w = 2 * kPi * double(f) / fps / period_s;
    rich(f, 4) = 0.3 * std::sin(w) + 0.15 * std::sin(2 * w);
  }
  CHECK(detect_cycles(planted, rich, fps, 1.0).period == Approx(period_s * fps).margin(1.0));
}

TEST_CASE("cycles: a take that does not repeat has none") {
  const double fps = 30.0;
  const Eigen::Index frames = 150;
  const Eigen::MatrixXd planted = Eigen::MatrixXd::Ones(frames, 2);
  CHECK(detect_cycles(planted, still_pose(frames), fps, 1.0).kind == CycleKind::kNone);  // standing
  Eigen::MatrixXd raise = still_pose(frames);  // both hands up once and down
  for (Eigen::Index f = 0; f < frames; ++f) {
    const double up = std::sin(kPi * double(f) / double(frames - 1));
    raise(f, 4) = raise(f, 7) = 0.5 * up * up;
  }
  const TakeCycles t = detect_cycles(planted, raise, fps, 1.0);
  CHECK(t.kind == CycleKind::kNone);
  CHECK(t.cycles.empty());
  CHECK_THROWS_AS(detect_cycles(Eigen::MatrixXd::Ones(10, 2), still_pose(11), fps, 1.0), InputError);
  CHECK_THROWS_AS(detect_cycles(planted, still_pose(frames), 0.0, 1.0), InputError);
  CycleOptions bad;
  bad.max_change = 1.5;
  CHECK_THROWS_AS(detect_cycles(planted, still_pose(frames), fps, 1.0, bad), InputError);
}

TEST_CASE("cycles: every real walk is gait cycles of about a second, over most of the take") {
  std::vector<std::string> files = test::asset_motions();
  for (const std::string& f : test::shared_motions()) files.push_back(f);
  REQUIRE(files.size() >= 4);
  for (const std::string& path : files) {
    for (const double fps : {30.0, 0.0}) {  // the working rate, and the file's own (120 fps for Bandai)
      INFO(path << " at " << (fps > 0 ? std::to_string(fps) : std::string("its own rate")));
      const auto clip = std::make_shared<const Clip>(read_motion_file(path));
      PrepareOptions o;
      o.fps = fps;
      const auto p = prepare_takes(std::vector<std::shared_ptr<const Clip>>{clip, clip}, o);
      const PreparedTake& take = p->reference();
      const TakeCycles t = detect_cycles(take.own_contacts, take.canonical.local, p->fps, p->feet.leg_length);
      REQUIRE(t.kind == CycleKind::kGait);
      const double frames = static_cast<double>(take.canonical.local.rows());
      INFO(t.cycles.size() << " cycles, median " << t.period / p->fps << " s, covering "
                           << t.frames_in_cycles() / frames);
      CHECK(t.period / p->fps > 0.6);  // brisk (angry: 0.8 s) to slow (sad: 1.7 s)
      CHECK(t.period / p->fps < 2.0);
      CHECK(t.frames_in_cycles() / frames > 0.6);
      for (size_t k = 1; k < t.cycles.size(); ++k) CHECK(t.cycles[k].begin >= t.cycles[k - 1].end);
    }
  }
}
