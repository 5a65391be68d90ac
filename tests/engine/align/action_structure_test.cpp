// The structure of an action (engine/align/action_structure.h, cycles.h action_structure_summary)
// and alignment by it (alignment.h align_by_structure): made-up takes of each kind (one stroke
// between rests, repeated strokes, gait, rest only), then the styled actions of
// ../shared/motions/actions, whose references must play whole in blends and mixes.
#include <cmath>
#include <fstream>
#include <memory>
#include <string>

#include <catch2/catch.hpp>

#include "engine/align/action_structure.h"
#include "engine/align/alignment.h"
#include "engine/align/cycles.h"
#include "engine/align/prepare_takes.h"
#include "engine/base/error.h"
#include "engine/io/motion_file.h"
#include "tests/engine/synthetic_gait.h"
#include "tests/test_data.h"

using namespace mostyle;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFps = 30.0;
// A span's ends are found within this many frames of where the made-up motion starts or stops
// (the speed is averaged over ActionSpanOptions::smoothing_s).
constexpr int kEdgeFrames = 6;

// Three joints (hips, head, hand) standing still: frames x 9, leg length 1.
Eigen::MatrixXd standing(Eigen::Index frames) {
  Eigen::MatrixXd local = Eigen::MatrixXd::Zero(frames, 9);
  local.col(1).setConstant(1.0);
  local.col(4).setConstant(1.6);
  local.col(7).setConstant(1.0);
  return local;
}

// Still for `before` s, the hand raised and lowered once over `stroke` s, still for `after` s.
Eigen::MatrixXd one_stroke(double before, double stroke, double after) {
  const int b = static_cast<int>(before * kFps), s = static_cast<int>(stroke * kFps), a = static_cast<int>(after * kFps);
  Eigen::MatrixXd local = standing(b + s + a);
  for (int f = 0; f < s; ++f) {
    const double up = std::sin(kPi * f / (s - 1));
    local(b + f, 7) += 0.6 * up * up;
    local(b + f, 6) += 0.3 * up * up;
  }
  return local;
}

// Still for `before` s, the hand raised, waved `strokes` times of `period` s, lowered, still for
// `after` s.
Eigen::MatrixXd waving(double before, int strokes, double period, double after) {
  const int b = static_cast<int>(before * kFps), ramp = static_cast<int>(0.5 * kFps);
  const int w = static_cast<int>(strokes * period * kFps), a = static_cast<int>(after * kFps);
  Eigen::MatrixXd local = standing(b + 2 * ramp + w + a);
  for (int f = 0; f < 2 * ramp + w; ++f) {
    const double lift = f < ramp ? double(f) / ramp : f >= ramp + w ? double(2 * ramp + w - f) / ramp : 1.0;
    local(b + f, 7) += 0.5 * lift;
    if (f >= ramp && f < ramp + w) local(b + f, 6) += 0.25 * std::sin(2 * kPi * (f - ramp) / (period * kFps));
  }
  return local;
}

TakeCycles cycles_of(const Eigen::MatrixXd& local) {
  return detect_cycles(Eigen::MatrixXd::Ones(local.rows(), 2), local, kFps, 1.0);
}

CanonicalMotion motion_of(const Eigen::MatrixXd& local) {
  CanonicalMotion m;
  m.local = local;
  m.ground = Eigen::MatrixXd::Zero(local.rows(), 2);
  m.heading = Eigen::VectorXd::Zero(local.rows());
  return m;
}

}  // namespace

TEST_CASE("action structure: one stroke between rests is one action, no loop, named so") {
  const Eigen::MatrixXd local = one_stroke(1.0, 1.5, 1.0);
  const ActionSpans spans = find_action_spans(local, kFps, 1.0);
  REQUIRE(spans.actions.size() == 1);
  CHECK(spans.rest_before == Approx(30).margin(kEdgeFrames));
  CHECK(spans.rest_after == Approx(30).margin(kEdgeFrames));
  CHECK(spans.rests_at_both_ends());
  CHECK(spans.mover == 2);  // the hand
  const TakeCycles t = cycles_of(local);
  CHECK(t.kind == CycleKind::kNone);
  CHECK_FALSE(t.loops());  // its first and last poses are alike because it stands, not because it repeats
  CHECK(cycle_loop_frames(local, kFps, 1.0) == 0);
  const std::string words = action_structure_summary(t, kFps);
  CHECK(words.rfind("one action (", 0) == 0);
  CHECK(words.find("between rests") != std::string::npos);
}

TEST_CASE("action structure: a hand held up between raising and lowering it is one action") {
  Eigen::MatrixXd local = one_stroke(0.8, 1.0, 0.8);
  const Eigen::MatrixXd held = waving(0.8, 0, 0.5, 0.8);  // raised, held 0 strokes, lowered
  const ActionSpans spans = find_action_spans(held, kFps, 1.0);
  CHECK(spans.actions.size() == 1);
  // Two strokes parted by a return to standing are two actions.
  Eigen::MatrixXd twice(2 * local.rows(), local.cols());
  twice << local, local;
  CHECK(find_action_spans(twice, kFps, 1.0).actions.size() == 2);
}

TEST_CASE("action structure: repeated strokes of a raised hand are periodic, counted within the action") {
  const Eigen::MatrixXd local = waving(1.0, 5, 0.7, 1.0);
  const TakeCycles t = cycles_of(local);
  REQUIRE(t.kind == CycleKind::kPeriodic);
  CHECK(t.cycles.size() >= 4);  // a stroke cut at the action's edge may be left out
  CHECK(t.cycles.size() <= 5);
  CHECK(t.period == Approx(0.7 * kFps).margin(2.0));
  CHECK(t.cycles.front().begin >= 30 - kEdgeFrames);  // not in the rest
  CHECK_FALSE(t.loops());
  CHECK(action_structure_summary(t, kFps).rfind("periodic: ", 0) == 0);
}

TEST_CASE("action structure: a take at rest throughout, and gait") {
  const Eigen::MatrixXd still = standing(120);
  const ActionSpans spans = find_action_spans(still, kFps, 1.0);
  CHECK(spans.still());
  CHECK(spans.rest_before == 120);
  CHECK(action_structure_summary(cycles_of(still), kFps) == "at rest throughout");
  // A little jitter is still rest.
  Eigen::MatrixXd jitter = still;
  for (Eigen::Index f = 0; f < jitter.rows(); ++f) jitter(f, 6) += 0.001 * ((f * 7919) % 13 - 6);
  CHECK(find_action_spans(jitter, kFps, 1.0).still());

  TakeCycles gait;
  gait.kind = CycleKind::kGait;
  gait.foot = 0;
  gait.cycles = {{0, 30}, {30, 60}, {60, 90}};
  CHECK(action_structure_summary(gait, kFps) == "gait: 3 cycles (left foot)");
}

TEST_CASE("action structure: bad options and inputs are refused") {
  ActionSpanOptions o;
  o.rest_share = 0.0;
  CHECK_THROWS_AS(find_action_spans(standing(10), kFps, 1.0, o), InputError);
  CHECK_THROWS_AS(find_action_spans(standing(10), 0.0, 1.0), InputError);
  CHECK_THROWS_AS(find_action_spans(standing(10), kFps, -1.0), InputError);
  CHECK(body_part_of("left_wrist") == "left hand");
  CHECK(body_part_of("right_ankle") == "right foot");
  CHECK(body_part_of("hips") == "body");
}

TEST_CASE("action structure: alignment by structure matches all of A, holding B's pose over a rest it lacks") {
  FeatureJoints joints;  // no feet or hands known: the body feature
  // A: a second of rest, the stroke, a second of rest. B: the stroke at once, slower, then rest.
  const Eigen::MatrixXd a = one_stroke(1.0, 1.2, 1.0), b = one_stroke(0.0, 1.8, 0.6);
  const ActionSpans sa = find_action_spans(a, kFps, 1.0), sb = find_action_spans(b, kFps, 1.0);
  REQUIRE(sb.rest_before == 0);
  const Alignment al = align_by_structure(motion_of(a), sa, motion_of(b), sb, joints, 1.0, kFps, AlignmentOptions());
  CHECK(al.by_structure);
  CHECK(al.a_first == 0);
  CHECK(al.a_last == a.rows() - 1);
  CHECK(al.warp.a[0] == Approx(0.0));
  CHECK(al.warp.a[al.warp.samples() - 1] == Approx(double(a.rows() - 1)));
  for (int k = 1; k < al.warp.samples(); ++k) {  // B only advances or holds: never a cut
    CHECK(al.warp.b[k] >= al.warp.b[k - 1] - 1e-9);
    CHECK(al.warp.b[k] - al.warp.b[k - 1] <= 4.0);
  }
  // Over A's rest before, B holds its first pose.
  CHECK(al.warp.b[0] == Approx(0.0).margin(0.5));
  REQUIRE_FALSE(al.notes.empty());
  CHECK(al.notes[0].find("B has no rest before its action") != std::string::npos);
  // B's rest after, which A lacks... here A has one; the other way round, A holds its first pose
  // while B's rest before plays: the path starts with a hold of A, so all of B is on it.
  const Alignment back = align_by_structure(motion_of(b), sb, motion_of(a), sa, joints, 1.0, kFps, AlignmentOptions());
  CHECK(back.b_first == 0);
  CHECK(back.b_last == a.rows() - 1);
  CHECK(back.path.front() == std::make_pair(0, 0));
  CHECK(back.path[1].first == 0);  // A held while B's rest plays
  REQUIRE_FALSE(back.notes.empty());
  CHECK(back.notes[0] == "A has no rest before its action: it holds its first pose while B's (0.0-1.0 s) plays");
  // A at rest throughout: matched with B's rest before, then holding its last pose while B's
  // action and rest after play: all of B.
  const Eigen::MatrixXd rest = standing(60);
  const Alignment still = align_by_structure(motion_of(rest), find_action_spans(rest, kFps, 1.0), motion_of(a), sa,
                                             joints, 1.0, kFps, AlignmentOptions());
  CHECK(still.a_last == 59);
  CHECK(still.b_first == 0);
  CHECK(still.b_last == a.rows() - 1);
  REQUIRE_FALSE(still.notes.empty());
  CHECK(still.notes[0].find("holds its last pose while B's action") != std::string::npos);
  CHECK(still.notes[0].find("left out") == std::string::npos);
  // Spans read on other frames are refused.
  CHECK_THROWS_AS(align_by_structure(motion_of(a), sb, motion_of(b), sb, joints, 1.0, kFps, AlignmentOptions()),
                  InputError);
}

namespace {

std::shared_ptr<const Clip> action(const std::string& name) {
  return std::make_shared<const Clip>(read_motion_file(test::shared_motion("actions/" + name + ".bvh")));
}

const char* const kStyled[][2] = {{"bandai_bye_", "not-confident"},
                                  {"bandai2_wave-left-hand_", "masculine"},
                                  {"bandai2_raise-up-right-hand_", "elderly"}};
const char* const kStyles[3][6] = {{"active", "childish", "feminine", "giant", "musical", "not-confident"},
                                   {"active", "elderly", "exhausted", "feminine", "masculine", "youthful"},
                                   {"active", "elderly", "exhausted", "feminine", "masculine", "youthful"}};

// Every frame of the reference (take 0) is a sample of the common timeline the mix plays, and
// every take is matched over all of it.
void check_reference_whole(const PreparedTakes& p) {
  const Eigen::VectorXd& reference = p.timeline.frames[0];
  CHECK(reference[0] == Approx(0.0));
  CHECK(reference[reference.size() - 1] == Approx(double(p.reference().canonical.local.rows() - 1)));
  for (int i = 1; i < p.size(); ++i) {
    CHECK(p.timeline.first[static_cast<size_t>(i)] == 0);
    CHECK(p.timeline.last[static_cast<size_t>(i)] == p.samples() - 1);
  }
}

}  // namespace

TEST_CASE("action structure: a styled action's blend and its seven-take mix play all of the normal take") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  if (test::shared_motion("actions/bandai_bye_normal.bvh").empty() ||
      !std::ifstream(test::shared_motion("actions/bandai_bye_normal.bvh"))) {
    WARN("skipped: ../shared/motions/actions is absent");
    return;
  }
  for (int family = 0; family < 3; ++family) {
    const std::string prefix = kStyled[family][0];
    INFO(prefix);
    std::vector<std::shared_ptr<const Clip>> takes{action(prefix + "normal")};
    for (const char* style : kStyles[family]) takes.push_back(action(prefix + style));
    for (size_t s = 1; s < takes.size(); ++s) {
      INFO(takes[s]->source);
      const auto pair = prepare_takes({takes[0], takes[s]}, PrepareOptions());
      check_reference_whole(*pair);
      CHECK(pair->takes[1].alignment.by_structure);
    }
    check_reference_whole(*prepare_takes(takes, PrepareOptions()));
  }
}

TEST_CASE("action structure: a looping action styled from another action's takes plays all of it") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  if (!std::ifstream(test::shared_motion("actions/bandai_respond_normal.bvh"))) {
    WARN("skipped: ../shared/motions/actions is absent");
    return;
  }
  // The respond take loops; the raised hand and the wave have no cycles its cycles register with.
  const auto content = action("bandai_respond_normal");
  for (const char* family : {"bandai2_raise-up-right-hand_", "bandai2_wave-left-hand_"}) {
    INFO(family);
    const auto p = prepare_takes({content, action(std::string(family) + "normal"), action(std::string(family) + "feminine")},
                                 PrepareOptions());
    REQUIRE(p->reference().cycles.loops());
    check_reference_whole(*p);
  }
}

TEST_CASE("action structure: no styled action or single action is read as a walk or a loop") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  if (!std::ifstream(test::shared_motion("actions/bandai_bye_normal.bvh"))) {
    WARN("skipped: ../shared/motions/actions is absent");
    return;
  }
  std::vector<std::string> names{"bandai_kick_normal", "bandai_punch_normal", "bandai_slash_normal",
                                 "bandai_call_normal"};
  for (int family = 0; family < 3; ++family) {
    names.push_back(std::string(kStyled[family][0]) + "normal");
    for (const char* style : kStyles[family]) names.push_back(std::string(kStyled[family][0]) + style);
  }
  for (const std::string& name : names) {
    INFO(name);
    const TakeCycles t = take_cycles(action(name));
    CHECK(t.kind != CycleKind::kGait);
    CHECK_FALSE(t.loops());
    const std::string words = action_structure_summary(t, 30.0);
    CHECK((words.rfind("periodic: ", 0) == 0 || words.find("action") != std::string::npos));
  }
  // Walks stay gait.
  const TakeCycles walk = take_cycles(std::make_shared<const Clip>(read_motion_file(test::shared_motion("bandai_walk_normal.bvh"))));
  CHECK(action_structure_summary(walk, 30.0).rfind("gait: ", 0) == 0);
}
