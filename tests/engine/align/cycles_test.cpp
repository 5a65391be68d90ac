// Cycles of a take (engine/align/cycles.h): strikes worked by hand; gait cycles of made-up
// stepping with pauses, uneven steps and flickering contacts; periods of a made-up wave with a
// still start, with a harmonic; none for a take that does not repeat; made-up bodies: loop clips
// with and without a repeated last frame, runs with flight phases, walks in place, a jump, a
// stand; the real walks of both conventions and frame rates, and the takes from the wild.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "engine/align/cycles.h"
#include "engine/align/loop_clip.h"
#include "engine/base/error.h"
#include "engine/io/motion_file.h"
#include "engine/prepare/canonical_frame.h"
#include "engine/align/prepare_takes.h"
#include "tests/engine/synthetic_gait.h"
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

// A made-up take's contacts and cycles as take_cycles finds a file's: its canonical frame, its
// loop, its contacts across the loop's end, its cycles with the body checked.
struct Detected {
  Eigen::MatrixXd contacts;
  TakeCycles cycles;
  int frames = 0;
  double covered() const { return double(cycles.frames_in_cycles()) / std::max(frames - 1, 1); }
};

Detected detect(const test::GaitSpec& g, int frames, const CycleOptions& o = {}) {
  const Eigen::MatrixXd world = test::gait_take(g, frames);
  const FootRig rig = test::gait_rig(g.fps);
  const CanonicalMotion canonical = to_canonical(world, 0, 1, 5);
  Detected d;
  d.frames = frames;
  d.contacts = detect_foot_contacts(world, rig, cycle_loop_frames(canonical.local, g.fps, rig.leg_length, o));
  d.cycles = detect_cycles(d.contacts, canonical.local, g.fps, rig.leg_length, o, test::gait_joints());
  return d;
}

// The frames of one cycle of g (rounded).
int cycle_frames(const test::GaitSpec& g) { return static_cast<int>(std::lround(g.cycle_s * g.fps)); }

}  // namespace

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

TEST_CASE("cycles: a loop clip whose last frame repeats its first is one gait cycle, its strikes read across its end") {
  test::GaitSpec g;  // a walk in place, 1 s at 30 fps, cut 30% into its cycle
  g.in_place = true;
  g.start = 0.3;
  const int n = cycle_frames(g);
  const Detected d = detect(g, n + 1);  // the last frame is the first again
  const TakeCycles& t = d.cycles;
  REQUIRE(t.kind == CycleKind::kGait);
  CHECK(t.loop_frames == n);
  REQUIRE(t.cycles.size() == 1);
  CHECK(t.cycles[0].begin == 0);
  CHECK(t.cycles[0].end == n);
  CHECK(t.period == n);
  CHECK(t.reason.empty());
  // The left foot lands 70% into the clip, the right 20% (detected a frame or two after the
  // ankle touches down, as the planted speed settles).
  CHECK(t.foot == 0);
  CHECK(t.strike_phase == Approx(0.7).margin(0.07));
  CycleOptions right;
  right.foot = 1;
  const Detected r = detect(g, n + 1, right);
  REQUIRE(r.cycles.kind == CycleKind::kGait);
  CHECK(r.cycles.foot == 1);
  CHECK(r.cycles.strike_phase == Approx(0.2).margin(0.07));
  // The left foot stands across the clip's end and start (planted 62% of the cycle from 70%).
  CHECK(d.contacts(0, 0) == 1.0);
  CHECK(d.contacts(n - 1, 0) == 1.0);
  CHECK(d.contacts.row(n) == d.contacts.row(0));  // the repeated frame is frame 0 again
}

TEST_CASE("cycles: a loop clip whose first frame follows its last, its root moving on, is one cycle to its end") {
  for (const double fps : {24.0, 60.0}) {
    test::GaitSpec g;  // a walk that travels (root motion), cut where the right foot lands
    g.fps = fps;
    g.start = 0.5;
    const int n = cycle_frames(g);
    INFO(fps << " fps");
    const Detected d = detect(g, n);  // frame n would be frame 0 again
    const TakeCycles& t = d.cycles;
    REQUIRE(t.kind == CycleKind::kGait);
    CHECK(t.loop_frames == n);
    REQUIRE(t.cycles.size() == 1);
    CHECK(t.cycles[0].begin == 0);
    CHECK(t.cycles[0].end == n);  // the whole clip: its end is frame 0 again
    CHECK(d.covered() > 1.0);
    CycleOptions left;
    left.foot = 0;
    CHECK(detect(g, n, left).cycles.strike_phase == Approx(0.5).margin(0.08));
  }
}

TEST_CASE("cycles: a take of several cycles that ends at its first pose is no loop; its cycles are cut at strikes") {
  test::GaitSpec g;
  const int n = cycle_frames(g);
  const Detected six = detect(g, 6 * n + 1);  // six seconds: longer than any loop
  CHECK(six.cycles.loop_frames == 0);
  CHECK(six.cycles.kind == CycleKind::kGait);
  CHECK(six.cycles.cycles.size() >= 5);
  g.cycle_s = 0.8;  // four cycles in 3.2 s: short enough, but the pose comes back three times
  const Detected four = detect(g, 4 * cycle_frames(g) + 1);
  CHECK(four.cycles.loop_frames == 0);
  CHECK(four.cycles.cycles.size() >= 3);
  for (const Cycle& c : four.cycles.cycles) CHECK(c.frames() == Approx(cycle_frames(g)).margin(1));
  // Two cycles may be a loop; its cycles are still those between strikes, inside it.
  const Detected two = detect(g, 2 * cycle_frames(g) + 1);
  CHECK(two.cycles.loop_frames == 2 * cycle_frames(g));
  REQUIRE(two.cycles.kind == CycleKind::kGait);
  REQUIRE(two.cycles.cycles.size() == 1);
  CHECK(two.cycles.cycles[0].frames() == Approx(cycle_frames(g)).margin(1));
  CHECK(two.cycles.strike_phase == 0.0);
}

TEST_CASE("cycles: runs with flight phases are gait cycles, cut or looped, travelling or in place") {
  test::GaitSpec g;  // 0.7 s cycles, each foot down 0.12 s: both feet in the air twice a cycle
  g.cycle_s = 0.7;
  g.stance = 0.17;
  g.stride = 0.5;
  g.lift = 0.3;
  g.fps = 120.0;
  g.start = 0.9;
  const Detected cut = detect(g, 120);  // a second of it, as a short styled clip is
  REQUIRE(cut.cycles.kind == CycleKind::kGait);
  CHECK(cut.cycles.loop_frames == 0);
  REQUIRE(cut.cycles.cycles.size() == 1);
  CHECK(cut.cycles.cycles[0].frames() == Approx(0.7 * 120).margin(2));
  CHECK(cut.covered() > 0.6);
  g.in_place = true;
  g.fps = 30.0;
  const Detected loop = detect(g, 21);  // a game's loop: 21 frames, the first following the last
  REQUIRE(loop.cycles.kind == CycleKind::kGait);
  CHECK(loop.cycles.loop_frames == 21);
  REQUIRE(loop.cycles.cycles.size() == 1);
  CHECK(loop.cycles.cycles[0].end == 21);
}

TEST_CASE("cycles: a walk in place (the planted foot sliding back under still hips) is gait cycles") {
  test::GaitSpec g;
  g.in_place = true;
  g.start = 0.45;
  const int n = cycle_frames(g);
  const Detected d = detect(g, static_cast<int>(5.5 * n));  // not a loop: it ends mid-cycle
  REQUIRE(d.cycles.kind == CycleKind::kGait);
  CHECK(d.cycles.loop_frames == 0);
  CHECK(d.cycles.cycles.size() >= 4);
  for (const Cycle& c : d.cycles.cycles) CHECK(c.frames() == Approx(n).margin(1));
}

TEST_CASE("cycles: a jump on both feet, a stand and a shuffle on the spot have no gait cycles, and say why") {
  test::GaitSpec jump;  // three jumps in place, landing on both feet, crouching at each landing
  jump.in_place = true;
  jump.together = true;
  jump.stance = 0.5;
  jump.stride = 0.05;
  jump.lift = 0.25;
  jump.crouch = 0.3;
  const Detected j = detect(jump, 3 * cycle_frames(jump) + 12);
  CHECK(j.cycles.kind != CycleKind::kGait);
  CHECK(j.cycles.reason == "the feet land together (a jump)");
  const Detected one = detect(jump, cycle_frames(jump) + 12);  // one jump: each foot strikes once
  CHECK(one.cycles.kind != CycleKind::kGait);
  CHECK(one.cycles.reason.rfind("the feet land together (a jump)", 0) == 0);
  test::GaitSpec stand;
  stand.in_place = true;
  stand.stride = 0.0;
  stand.lift = 0.0;
  const Detected s = detect(stand, 90);
  CHECK(s.cycles.kind == CycleKind::kNone);
  CHECK(s.cycles.reason.rfind("no foot strike of the left foot", 0) == 0);
  test::GaitSpec shuffle = stand;  // the feet step in turn, but on the spot
  shuffle.lift = 0.1;
  shuffle.stride = 0.04;
  const Detected sh = detect(shuffle, 4 * cycle_frames(shuffle) + 7);
  CHECK(sh.cycles.kind == CycleKind::kNone);  // stepping in turn: no other repeated action either
  CHECK(sh.cycles.reason == "the feet do not step: they move little against the body");
  test::GaitSpec low;  // a walk with the hips at under half the leg's height
  Eigen::MatrixXd world = test::gait_take(low, 4 * cycle_frames(low));
  // (The hips lowered by 0.4 m: the legs no longer reach the ground, but the checks read only heights.)
  for (Eigen::Index f = 0; f < world.rows(); ++f) world(f, 1) -= 0.4;
  const FootRig rig = test::gait_rig(low.fps);
  const CanonicalMotion c = to_canonical(world, 0, 1, 5);
  const TakeCycles t = detect_cycles(detect_foot_contacts(world, rig), c.local, low.fps, rig.leg_length, {},
                                     test::gait_joints());
  CHECK(t.kind == CycleKind::kNone);
  CHECK(t.reason == "the hips are low (not walking or running)");
}

TEST_CASE("cycles: a loop's length, measured on the pose alone") {
  test::GaitSpec g;
  g.in_place = true;
  const int n = cycle_frames(g);
  const CanonicalMotion repeat = to_canonical(test::gait_take(g, n + 1), 0, 1, 5);
  CHECK(loop_clip_frames(repeat.local, 1000, 1) == n);
  const CanonicalMotion follow = to_canonical(test::gait_take(g, n), 0, 1, 5);
  CHECK(loop_clip_frames(follow.local, 1000, 1) == n);
  CHECK(loop_clip_frames(follow.local, n - 1, 1) == 0);  // longer than allowed
  const CanonicalMotion cut = to_canonical(test::gait_take(g, n - 7), 0, 1, 5);
  CHECK(loop_clip_frames(cut.local, 1000, 1) == 0);  // ends mid-cycle
  CHECK(loop_clip_frames(Eigen::MatrixXd::Zero(40, 27), 1000, 1) == 0);  // still
  CHECK(loop_clip_frames(Eigen::MatrixXd::Ones(3, 27), 1000, 1) == 0);   // too short
  CHECK_THROWS_AS(detect_cycles(Eigen::MatrixXd::Zero(10, 2), Eigen::MatrixXd::Zero(10, 27), 30.0, 1.0, {},
                                GaitJoints{9, {{3, 7}}}),
                  InputError);
}

TEST_CASE("cycles: takes from the wild: loops, short clips, runs, in place, any units and rates") {
  if (test::shared_motion("wild/README.md").empty()) {
    WARN("skipped: ../shared/motions/wild is absent");
    return;
  }
  // Each is a walk or a run of about one cycle or more.
  const char* gaits[] = {"gltf_cesiumman_walk.glb", "gltf_godot_mixamo_walk_run.glb#walking",
                         "gltf_godot_mixamo_walk_run.glb#running", "gltf_godot_robot_walk_run.glb#walk",
                         "gltf_godot_robot_walk_run.glb#run", "gltf_mannequiny_run.glb#run_root.001",
                         "fbx_mixamo_walking.fbx", "xia_sexy_01.bvh", "xia_angry_13.bvh", "xia_old_13.bvh",
                         "xia_depressed_13.bvh", "aalto_t_walk_regular.bvh", "aalto_k_walk_fast.bvh",
                         "aalto_k_walk_slow.bvh"};
  for (const char* name : gaits) {
    INFO(name);
    const auto clip = std::make_shared<const Clip>(read_motion_file(test::shared_motion("wild/") + name));
    const TakeCycles t = take_cycles(clip);
    INFO(cycle_kind_name(t.kind) << ", " << t.cycles.size() << " cycles, " << t.reason);
    CHECK(t.kind == CycleKind::kGait);
    CHECK(double(t.frames_in_cycles()) / (clip->frames() - 1) >= 0.6);
  }
  // A get-up, a jump, a kick and standing are none.
  const char* others[] = {"gltf_godot_mixamo_walk_run.glb#get_up", "xia_neutral_16.bvh",
                          "gltf_godot_mixamo_walk_run.glb#kick", "gltf_godot_mixamo_walk_run.glb#idle",
                          "gltf_godot_robot_walk_run.glb#idle"};
  for (const char* name : others) {
    INFO(name);
    const TakeCycles t =
        take_cycles(std::make_shared<const Clip>(read_motion_file(test::shared_motion("wild/") + name)));
    CHECK(t.kind != CycleKind::kGait);
    CHECK_FALSE(t.reason.empty());
    if (std::string(name) == "xia_neutral_16.bvh") CHECK(t.reason.rfind("the feet land together (a jump)", 0) == 0);
  }
}

TEST_CASE("cycles: the wild's short clips keep their cycles at the working rates 24 and 30 fps") {
  // A 120 fps Xia walk whose foot lands in its last 25 ms loses that landing when read at 30 or
  // 24 fps (the working rate's last frame comes before it): its cycles are then its own rate's,
  // carried to the working rate, and a blend of two such clips is registered by cycles, covering
  // the first whole (it was aligned whole, from its third frame).
  if (test::shared_motion("wild/README.md").empty()) {
    WARN("skipped: ../shared/motions/wild is absent");
    return;
  }
  const char* clips[] = {"xia_angry_13.bvh", "xia_depressed_13.bvh", "xia_old_13.bvh", "xia_sexy_01.bvh"};
  for (double fps : {24.0, 30.0}) {
    for (const char* name : clips) {
      INFO(name << " at " << fps << " fps");
      const auto clip = std::make_shared<const Clip>(read_motion_file(test::shared_motion("wild/") + name));
      PrepareOptions options;
      options.fps = fps;
      const auto prepared = prepare_takes({clip, clip}, options);
      const TakeCycles& cycles = prepared->reference().cycles;
      INFO(cycle_kind_name(cycles.kind) << ", " << cycles.reason);
      CHECK(cycles.kind == CycleKind::kGait);
      REQUIRE_FALSE(cycles.cycles.empty());
      CHECK(cycles.cycles.back().end < prepared->reference().world.rows());
    }
    const auto a = std::make_shared<const Clip>(read_motion_file(test::shared_motion("wild/xia_angry_13.bvh")));
    const auto b = std::make_shared<const Clip>(read_motion_file(test::shared_motion("wild/xia_depressed_13.bvh")));
    PrepareOptions options;
    options.fps = fps;
    const auto pair = prepare_takes({a, b}, options);
    INFO("at " << fps << " fps: " << pair->takes[1].alignment.whole_because);
    CHECK(pair->takes[1].alignment.whole_because.empty());
    CHECK(pair->timeline.frames[0][0] == 0.0);
    CHECK(pair->timeline.frames[0][pair->timeline.samples() - 1] == Approx(pair->reference().world.rows() - 1));
  }
}

TEST_CASE("cycles: take_cycles reads the legs alone and finds what preparing the take as a reference finds") {
  // take_cycles runs FK on the hips and legs only (the whole body only where the feet give no
  // gait); preparing the take with itself at its own rate reads the same columns of the whole
  // pose, so the two agree cycle for cycle, for gait takes and for others.
  const char* names[] = {"wild/gltf_cesiumman_walk.glb", "wild/gltf_godot_mixamo_walk_run.glb#running",
                         "wild/xia_old_13.bvh", "wild/aalto_k_walk_slow.bvh", "wild/xia_neutral_16.bvh",
                         "wild/gltf_godot_mixamo_walk_run.glb#idle", "bandai_walk_old.bvh"};
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  for (const char* name : names) {
    INFO(name);
    const auto clip = std::make_shared<const Clip>(read_motion_file(test::shared_motion("") + name));
    PrepareOptions options;
    options.fps = 0.0;
    const auto prepared = prepare_takes({clip, clip}, options);
    const TakeCycles own = take_cycles(clip);
    const TakeCycles& ref = prepared->reference().cycles;
    CHECK(own.kind == ref.kind);
    CHECK(own.foot == ref.foot);
    CHECK(own.loop_frames == ref.loop_frames);
    REQUIRE(own.cycles.size() == ref.cycles.size());
    for (size_t k = 0; k < own.cycles.size(); ++k) {
      CHECK(own.cycles[k].begin == ref.cycles[k].begin);
      CHECK(own.cycles[k].end == ref.cycles[k].end);
    }
  }
}
