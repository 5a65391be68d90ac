// Registration by cycles (engine/align/cycle_registration.h): a short take's cycles reused in
// order over a long reference, and on real walks of different lengths, every cycle of the
// reference matched; then the registered motion itself.
#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "engine/align/alignment.h"
#include "engine/align/cycle_registration.h"
#include "engine/base/error.h"
#include "engine/io/motion_file.h"
#include "engine/align/prepare_takes.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/units.h"
#include "tests/engine/transfer_run.h"
#include "tests/test_data.h"

using namespace mostyle;

TEST_CASE("cycle registration: a short take's cycles reused in order, worked by hand") {
  TakeCycles reference, take;
  reference.cycles = {{10, 40}, {40, 70}, {80, 100}, {100, 130}, {130, 160}};  // a pause at 70-80
  take.cycles = {{0, 15}, {15, 33}};
  // Its own two, then its last three slots' worth again in order, ending on its last, so that
  // its stop follows: 0 1 | 1 0 1.
  const std::vector<int> pairs = pair_cycles(reference, take);
  CHECK(pairs == std::vector<int>{0, 1, 1, 0, 1});
  CHECK(replay_cycle(0, 2, 5) == 0);
  CHECK(replay_cycle(4, 2, 5) == 1);
  TakeCycles three;
  three.cycles = {{0, 10}, {10, 20}, {20, 30}};
  CHECK(pair_cycles(reference, three) == std::vector<int>{0, 1, 2, 1, 2});  // the last two again
  // Nothing to pair: no cycles on either side.
  CHECK(pair_cycles(reference, TakeCycles()).empty());
  CHECK(pair_cycles(TakeCycles(), take).empty());
}

TEST_CASE("cycle registration: a 6.5 s walk covers every cycle of a 22 s one") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  const auto content = std::make_shared<const Clip>(read_motion_file(test::shared_motion("cmu142_walk_joy.bvh")));
  const auto neutral = std::make_shared<const Clip>(read_motion_file(test::shared_motion("bandai_walk_normal.bvh")));
  const auto p = prepare_takes(std::vector<std::shared_ptr<const Clip>>{content, neutral}, PrepareOptions());
  const TakeCycles& ref = p->takes[0].cycles;
  const TakeCycles& other = p->takes[1].cycles;
  REQUIRE(ref.cycles.size() > other.cycles.size());  // the style take is the shorter
  const std::vector<int> pairs = pair_cycles(ref, other);
  CHECK(pairs.size() == ref.cycles.size());  // every cycle of the reference is matched
  // Every cycle of the short take is used, its own in order first, then again in order, the
  // last slot its last cycle.
  const int n = static_cast<int>(other.cycles.size()), slots = static_cast<int>(pairs.size());
  for (int k = 0; k < slots; ++k) CHECK(pairs[static_cast<size_t>(k)] == (k < n ? k : ((k - slots) % n + n) % n));
  CHECK(pairs.back() == n - 1);
  CHECK(pairs.size() >= 2 * other.cycles.size());
}

namespace {

// Gait cycles starting at `foot`'s strikes, of the given frames and median length.
TakeCycles gait(std::vector<Cycle> cycles, int foot, double period = 0.0) {
  TakeCycles c;
  c.kind = CycleKind::kGait;
  c.foot = foot;
  c.cycles = std::move(cycles);
  c.period = period;
  return c;
}

// A made-up motion of one joint: x a ramp (its frame number, so a frame can be read back from its
// pose), y `level`, z 0; walking along +z at one unit a frame, facing +z.
CanonicalMotion ramp_motion(int frames, double level) {
  CanonicalMotion m;
  m.local.resize(frames, 3);
  m.ground.resize(frames, 2);
  m.heading = Eigen::VectorXd::Zero(frames);
  for (int f = 0; f < frames; ++f) {
    m.local.row(f) << f, level, 0.0;
    m.ground.row(f) << 0.0, f;
  }
  return m;
}

Eigen::MatrixXd contacts_marked(int frames, double value) { return Eigen::MatrixXd::Constant(frames, 2, value); }

// ramp_motion's one joint, its movement kept as it is by a posture.
const std::vector<bool> kOneJointUnsized{false};

}  // namespace

TEST_CASE("cycle registration: the registered take, worked by hand") {
  // The reference: 100 frames, cycles at 10-35, 35-60 and 70-95 (a pause at 60-70). The take: 40
  // frames, cycles 5-20 and 20-35.
  const CanonicalMotion ref = ramp_motion(100, 1.0), take = ramp_motion(40, 3.0);
  const TakeCycles rc = gait({{10, 35}, {35, 60}, {70, 95}}, 0), tc = gait({{5, 20}, {20, 35}}, 0, 15);
  const RegisteredMotion r = register_by_cycles(ref, contacts_marked(100, 0.0), rc, take, contacts_marked(40, 1.0), tc, 2);
  const CycleRegistration& g = r.registration;
  CHECK(g.pairs == std::vector<int>{0, 1, 1});
  // Spans: the take's own 5 frames before its first cycle (both under way there; the reference's
  // 10 are more than 1.5 times as many, so the reference's first 5 hold the take's first frame),
  // 15 + 15 (the take's cycles), 10 of the pause, 15 (its last cycle again), 5 after (its own
  // stop, which follows its last cycle).
  REQUIRE(r.motion.local.rows() == 5 + 15 + 15 + 10 + 15 + 5);
  REQUIRE(g.cycles.cycles.size() == 3);
  CHECK(g.cycles.cycles[0].begin == 5);
  CHECK(g.cycles.cycles[1].begin == 20);
  CHECK(g.cycles.cycles[2].begin == 45);
  CHECK(g.cycles.cycles[2].end == 60);
  // Inside cycles: the take's own frames (x reads the frame back) and contacts; the take's cycle
  // 1 follows its cycle 0 directly (20), so no seam is eased.
  for (int v = 0; v < 35; ++v) {
    const double own = v;
    CHECK(r.motion.local(v, 0) == Approx(own));
    CHECK(r.motion.local(v, 1) == Approx(3.0));
    CHECK(g.source[v] == own);
    CHECK(g.source_cycle[v] == (v < 5 ? -1 : v < 20 ? 0 : 1));
    CHECK(r.contacts(v, 0) == 1.0);
  }
  CHECK(g.source[45] == 20.0);  // the take's last cycle again
  CHECK(g.source_cycle[59] == 1);
  // In the middle of the pause (fade of 2 frames): the reference moved by the posture offset,
  // the take's mean over its cycles minus the reference's.
  const double ref_mean_x = (22.0 * 25 + 47.0 * 25 + 82.0 * 25) / 75.0;  // cycles' own means: 22, 47, 82
  const double take_mean_x = (12.0 * 15 + 27.0 * 15) / 30.0;             // 12, 27
  const int middle = 35 + 5;                                             // reference frame 65
  CHECK(r.motion.local(middle, 0) == Approx(65 + take_mean_x - ref_mean_x));
  CHECK(r.motion.local(middle, 1) == Approx(1.0 + 2.0));
  CHECK(std::isnan(g.source[middle]));
  CHECK(g.source_cycle[middle] == -1);
  CHECK(r.contacts(middle, 0) == 0.0);  // the reference's
  // Right after a cycle: the take running on from it (its frame 35), fully weighted.
  CHECK(r.motion.local(35, 0) == Approx(35.0));
  CHECK(g.source[35] == 35.0);
  // Anchors: each span's start (the start's two: the hold, then 1:1), then the ends.
  REQUIRE(g.anchors.size() == 8);
  CHECK(g.anchors[0].hold);
  CHECK(g.anchors[1].reference == 5);
  CHECK(g.anchors[1].registered == 0);
  CHECK(g.anchors[2].reference == 10);
  CHECK(g.anchors[2].registered == 5);
  CHECK(g.anchors[2].cycle);
  CHECK(g.anchors[4].reference == 60);
  CHECK(g.anchors[4].registered == 35);
  CHECK_FALSE(g.anchors[4].cycle);
  CHECK(g.anchors.back().reference == 99);
  CHECK(g.anchors.back().registered == 64);
  // The root: the take's steps (one unit a frame along +z) throughout, from the reference's start.
  CHECK(r.motion.ground(0, 1) == Approx(0.0));
  CHECK(r.motion.ground(64, 1) == Approx(64.0));
}

TEST_CASE("cycle registration: a start and a stop show the take's own where both takes are alike there") {
  // The reference: 60 frames, cycles 10-30 and 30-50. The take: 70 frames, cycles 15-35, 35-50 and
  // 50-60 (more than the reference's), its stop 60-70 after its last cycle.
  const CanonicalMotion ref = ramp_motion(60, 1.0), take = ramp_motion(70, 3.0);
  const TakeCycles rc = gait({{10, 30}, {30, 50}}, 0, 20), tc = gait({{15, 35}, {35, 50}, {50, 60}}, 0, 15);
  const RegisteredMotion r = register_by_cycles(ref, contacts_marked(60, 0.0), rc, take, contacts_marked(70, 1.0), tc, 2);
  const CycleRegistration& g = r.registration;
  // Start: the take's frames 0-14; cycles 0 and 1 (35 frames); stop: its frames 60-69, after its
  // cycle 1 that ends at 50, not at 60: the seam (50 - 60) shrinks linearly over the stop.
  REQUIRE(r.motion.local.rows() == 15 + 35 + 10);
  CHECK(g.source[0] == 0.0);
  CHECK(g.source[14] == 14.0);
  CHECK(g.source[50] == 60.0);
  CHECK(r.motion.local(50, 0) == Approx(50.0));
  CHECK(r.motion.local(55, 0) == Approx(65.0 - 10.0 * 0.5));
  CHECK(g.source[59] == 69.0);
  CHECK(r.contacts(59, 0) == 1.0);
  CHECK(g.anchors.front().cycle);
  CHECK(g.anchors[g.anchors.size() - 2].cycle);

  // The same take standing at its start (its root still over its first frames) while the
  // reference is under way: its start is not the reference's, which shows its posture instead
  // (the reference's own frames, moved), the take's frames only near its first cycle.
  CanonicalMotion standing = take;
  for (int f = 0; f < 15; ++f) standing.ground.row(f) << 0.0, 0.0;
  const RegisteredMotion s = register_by_cycles(ref, contacts_marked(60, 0.0), rc, standing, contacts_marked(70, 1.0), tc, 2);
  REQUIRE(s.motion.local.rows() == 10 + 35 + 10);
  CHECK_FALSE(s.registration.anchors.front().cycle);
  CHECK(std::isnan(s.registration.source[0]));
  CHECK(s.registration.anchors[s.registration.anchors.size() - 2].cycle);
}

TEST_CASE("cycle registration: a start or stop far longer in one take is matched next to the cycle, the rest held") {
  // The reference: 60 frames, its start 0-2 before cycles 2-22 and 22-42, its stop 42-60 (18
  // frames). The take: 48 frames, its start 0-12 (12 frames), cycles 12-27 and 27-45, its stop
  // 45-48 (3 frames). Both under way at both ends. Beyond 1.5 times each other's length.
  const CanonicalMotion ref = ramp_motion(60, 1.0), take = ramp_motion(48, 3.0);
  const TakeCycles rc = gait({{2, 22}, {22, 42}}, 0, 20), tc = gait({{12, 27}, {27, 45}}, 0, 16);
  const RegisteredMotion r = register_by_cycles(ref, contacts_marked(60, 0.0), rc, take, contacts_marked(48, 1.0), tc, 2);
  const CycleRegistration& g = r.registration;
  // The take's own start, cycles and stop, every frame of it once: 12 + 33 + 3.
  REQUIRE(r.motion.local.rows() == 48);
  for (int v = 0; v < 48; ++v) CHECK(g.source[v] == double(v));
  // Start: the reference held at its frame 0 over the take's first 10 frames, then 2 frames 1:1
  // into the first cycle. Stop: 3 frames 1:1 from the last cycle, then the take held at its last
  // frame over the reference's other 15.
  using A = CycleRegistration::Anchor;
  auto is = [](const A& a, int reference, int registered, bool cycle, bool hold) {
    return a.reference == reference && a.registered == registered && a.cycle == cycle && a.hold == hold;
  };
  REQUIRE(g.anchors.size() == 7);
  CHECK(is(g.anchors[0], 0, 0, false, true));
  CHECK(is(g.anchors[1], 0, 10, false, false));
  CHECK(is(g.anchors[2], 2, 12, true, false));
  CHECK(is(g.anchors[3], 22, 27, true, false));
  CHECK(is(g.anchors[4], 42, 45, false, false));
  CHECK(is(g.anchors[5], 44, 47, false, true));
  CHECK(is(g.anchors[6], 59, 47, false, false));
  // The warp follows them: every frame of both takes on it, the holds as steps of one take alone.
  const Alignment al = align_by_cycles(ref, r, FeatureJoints{0, 0, 0, 0}, 1.0, 30.0, AlignmentOptions(), nullptr);
  auto has = [&](int i, int j) {
    return std::find(al.path.begin(), al.path.end(), std::make_pair(i, j)) != al.path.end();
  };
  for (int j = 0; j <= 10; ++j) CHECK(has(0, j));
  CHECK(has(1, 11));
  for (int i = 44; i < 60; ++i) CHECK(has(i, 47));
  CHECK(al.path.back() == std::make_pair(59, 47));
  // Said in words, and not flagged as poor matches (a held pose against one that moves).
  REQUIRE(al.notes.size() == 2);
  CHECK(al.notes[0] == "B's start is longer than A's: A holds its first pose while B's first 0.3 s play (none of them "
                       "on A's clock)");
  CHECK(al.notes[1] == "A's stop is longer than B's: B holds its last pose over A's last 0.5 s (none of them at B's "
                       "weight 1)");
  for (const auto& [k, end] : al.poor) CHECK((al.warp.a[k] > 0.5 && al.warp.a[end] < 43.5));
}

TEST_CASE("cycle registration: a reused cycle that does not follow on eases its seam over the cycle") {
  const CanonicalMotion ref = ramp_motion(100, 1.0), take = ramp_motion(40, 3.0);
  const TakeCycles rc = gait({{10, 30}, {30, 50}, {50, 70}}, 1), tc = gait({{5, 20}, {20, 35}}, 1);  // one after another
  const RegisteredMotion r = register_by_cycles(ref, contacts_marked(100, 0.0), rc, take, contacts_marked(40, 1.0), tc, 2);
  // The third cycle is the take's last (second) again, after itself: at the seam the pose goes on
  // from where it ended (the take's frame 35), and the difference (35 - 20) shrinks linearly to
  // nothing by the cycle's end.
  const int v = r.registration.cycles.cycles[2].begin;  // 5 + 15 + 15 (the take's own start)
  REQUIRE(v == 35);
  CHECK(r.motion.local(v, 0) == Approx(35.0));
  CHECK(r.motion.local(v + 5, 0) == Approx(25.0 + 15.0 * (1.0 - 5.0 / 15.0)));
  CHECK(r.motion.local(v + 14, 0) == Approx(34.0 + 15.0 / 15.0));
  CHECK(r.registration.source[v] == 35.0);  // the seam's first frame shows the pose the cycle before ended on
  CHECK(r.registration.source[v + 1] == 21.0);
}

TEST_CASE("cycle registration: takes that cannot be registered are refused, and say why") {
  const CanonicalMotion ref = ramp_motion(100, 1.0), take = ramp_motion(40, 3.0);
  TakeCycles rc, tc;
  rc.kind = tc.kind = CycleKind::kGait;
  rc.foot = 0;
  tc.foot = 1;
  rc.cycles = {{10, 35}};
  tc.cycles = {{5, 20}};
  CHECK_FALSE(cycles_register(rc, tc));  // different feet
  CHECK_THROWS_AS(register_by_cycles(ref, contacts_marked(100, 0), rc, take, contacts_marked(40, 0), tc, 2), InputError);
  tc.foot = 0;
  CHECK(cycles_register(rc, tc));
  tc.kind = CycleKind::kPeriodic;
  CHECK_FALSE(cycles_register(rc, tc));  // different kinds
  CHECK_FALSE(cycles_register(TakeCycles(), rc));
  tc.kind = CycleKind::kGait;
  tc.cycles = {{5, 45}};  // past the take's 40 frames
  CHECK_THROWS_WITH(register_by_cycles(ref, contacts_marked(100, 0), rc, take, contacts_marked(40, 0), tc, 2),
                    Catch::Contains("does not fit its 40 frames"));
}

TEST_CASE("cycle registration: a 6.5 s walk registered onto a 22 s one covers it whole, at every weight") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  const auto content = std::make_shared<const Clip>(read_motion_file(test::shared_motion("cmu142_walk_joy.bvh")));
  const auto neutral = std::make_shared<const Clip>(read_motion_file(test::shared_motion("bandai_walk_normal.bvh")));
  const auto p = prepare_takes(std::vector<std::shared_ptr<const Clip>>{content, neutral}, PrepareOptions());
  const PreparedTake& ref = p->takes[0];
  const PreparedTake& other = p->takes[1];
  REQUIRE_FALSE(other.registration.empty());
  const Alignment& al = other.alignment;
  CHECK(al.by_cycles());
  const int frames = static_cast<int>(ref.canonical.local.rows());
  // The warp runs over all of both, monotone.
  CHECK(al.warp.a[0] == Approx(0.0));
  CHECK(al.warp.a[al.warp.samples() - 1] == Approx(frames - 1));
  CHECK(al.warp.b[0] == Approx(0.0));
  CHECK(al.warp.b[al.warp.samples() - 1] == Approx(other.canonical.local.rows() - 1));
  for (int k = 1; k < al.warp.samples(); ++k) {
    CHECK(al.warp.a[k] >= al.warp.a[k - 1]);
    CHECK(al.warp.b[k] >= al.warp.b[k - 1]);
  }
  CHECK(al.a_first == 0);
  CHECK(al.a_last == frames - 1);
  // One registered cycle per reference cycle, each the length of the take's cycle it shows.
  REQUIRE(other.registration.cycles.cycles.size() == ref.cycles.cycles.size());
  for (size_t k = 0; k < ref.cycles.cycles.size(); ++k) {
    const Cycle& own = other.registration.take_cycles.cycles[static_cast<size_t>(other.registration.pairs[k])];
    CHECK(other.registration.cycles.cycles[k].frames() == own.frames());
  }
  // The common timeline covers the whole reference.
  CHECK(p->timeline.frames[0][0] == Approx(0.0));
  CHECK(p->timeline.frames[0][p->samples() - 1] == Approx(frames - 1));
  CHECK(p->timeline.first[1] == 0);
  CHECK(p->timeline.last[1] == p->samples() - 1);
  // The take's own frames back from its timeline's: inside cycles within the take.
  const Eigen::VectorXd own = frames_in_take(other, other.frames);
  int inside = 0;
  for (Eigen::Index k = 0; k < own.size(); ++k)
    if (!std::isnan(own[k])) {
      ++inside;
      CHECK(own[k] >= 0.0);
      CHECK(own[k] <= double(other.registration.take_cycles.cycles.back().end) + p->fps);
    }
  CHECK(inside > 0.6 * own.size());
  // Aligned whole instead, the take covers only part of the reference.
  PrepareOptions whole;
  whole.align.time_base = TimeBase::kWhole;
  const auto w = prepare_takes(std::vector<std::shared_ptr<const Clip>>{content, neutral}, whole);
  CHECK(w->takes[1].registration.empty());
  CHECK(w->takes[1].alignment.a_last - w->takes[1].alignment.a_first < frames / 2);
}

TEST_CASE("posture registration: a walk on a reference with no cycles gives its mean pose, worked by hand") {
  // Reference: 6 frames, x = 0..5 (mean 2.5), y = 1. Take: 20 frames, x = 0..19, y = 5, cycles over
  // frames 4-11 (mean x 7.5). Posture: (5, 4, 0).
  const CanonicalMotion reference = ramp_motion(6, 1.0), take = ramp_motion(20, 5.0);
  TakeCycles cycles;
  cycles.kind = CycleKind::kGait;
  cycles.foot = 0;
  cycles.cycles = {{4, 8}, {8, 12}};
  const RegisteredMotion r =
      register_posture_only(reference, contacts_marked(6, 1.0), take_posture(take.local, cycles), cycles, kOneJointUnsized, 1.0);
  REQUIRE(r.motion.local.rows() == 6);
  for (int f = 0; f < 6; ++f) {
    CHECK(r.motion.local(f, 0) == Approx(f + 5.0));
    CHECK(r.motion.local(f, 1) == Approx(5.0));
    CHECK(r.motion.local(f, 2) == Approx(0.0).margin(1e-12));
    CHECK(std::isnan(r.registration.source[f]));
    CHECK(r.registration.source_cycle[f] == -1);
  }
  CHECK(r.motion.ground == reference.ground);  // the reference's root and contacts
  CHECK(r.motion.heading == reference.heading);
  CHECK(r.contacts == contacts_marked(6, 1.0));
  CHECK(r.registration.posture_only());
  CHECK_FALSE(r.registration.empty());
  REQUIRE(r.registration.anchors.size() == 2);
  CHECK(r.registration.anchors[1].reference == 5);
  CHECK(r.registration.anchors[1].registered == 5);
  // A loop's cycle read across its end: a 10-frame loop's cycle 5-15 is frames 5-9 and 0-4
  // (mean x 4.5).
  TakeCycles loop;
  loop.kind = CycleKind::kGait;
  loop.loop_frames = 10;
  loop.cycles = {{5, 15}};
  const RegisteredMotion l =
      register_posture_only(reference, contacts_marked(6, 0.0), take_posture(ramp_motion(10, 1.0).local, loop), loop,
                            kOneJointUnsized, 1.0);
  CHECK(l.motion.local(0, 0) == Approx(0.0 + 4.5 - 2.5));
  // A pose of another skeleton's size is refused.
  TakePosture other = take_posture(take.local, cycles);
  other.mean.resize(2);
  CHECK_THROWS_AS(register_posture_only(reference, contacts_marked(6, 0.0), other, loop, kOneJointUnsized, 1.0), InputError);
}

TEST_CASE("posture of a take: its mean pose and spread, and the reference's movement sized by it, worked by hand") {
  // Take: 10 frames, x = 0, 2, .., 18, y = 2, no cycles: mean x 9, spread 2 sqrt(8.25) (the RMS of
  // x - 9), fastest 2 a frame. Reference: 6 frames, x = 0..5, y = 1: mean x 2.5, spread
  // sqrt(17.5 / 6), fastest 1.
  CanonicalMotion take = ramp_motion(10, 2.0);
  take.local.col(0) *= 2.0;
  const CanonicalMotion reference = ramp_motion(6, 1.0);
  const TakePosture posture = take_posture(take.local, TakeCycles());
  CHECK(posture.mean[0] == Approx(9.0));
  CHECK(posture.mean[1] == Approx(2.0));
  CHECK(posture.spread[0] == Approx(2.0 * std::sqrt(8.25)));
  CHECK(posture.fastest[0] == Approx(2.0));
  // A walk's posture is over its cycles, its mean the one cycles_mean_pose gives.
  TakeCycles cycles;
  cycles.kind = CycleKind::kGait;
  cycles.cycles = {{4, 8}, {8, 12}};
  const CanonicalMotion walk = ramp_motion(20, 5.0);
  CHECK(take_posture(walk.local, cycles).mean.isApprox(cycles_mean_pose(walk.local, cycles)));
  CHECK(take_posture(walk.local, cycles).spread[0] == Approx(std::sqrt(5.25)));  // x = 4..11 about 7.5
  // The spreads' ratio, 2 sqrt(8.25) / sqrt(17.5 / 6) = 3.4, would move x 3.4 a frame, faster than
  // the take's 2: sized by 2. x = 9 + (f - 2.5) 2; y keeps the reference's (still) 1, moved to 2.
  const RegisteredMotion r =
      register_posture_only(reference, contacts_marked(6, 1.0), posture, TakeCycles(), {true}, 1.0);
  for (int f = 0; f < 6; ++f) {
    CHECK(r.motion.local(f, 0) == Approx(9.0 + (f - 2.5) * 2.0));
    CHECK(r.motion.local(f, 1) == Approx(2.0));
  }
  CHECK(r.registration.posture_only());
  // The reference's spread taken as at least the floor (3 here): sized by 2 sqrt(8.25) / 3 = 1.9.
  const RegisteredMotion floored =
      register_posture_only(reference, contacts_marked(6, 1.0), posture, TakeCycles(), {true}, 3.0);
  CHECK(floored.motion.local(0, 0) == Approx(9.0 - 2.5 * 2.0 * std::sqrt(8.25) / 3.0));
  // Not sized: moved by the posture alone.
  const RegisteredMotion unsized =
      register_posture_only(reference, contacts_marked(6, 1.0), posture, TakeCycles(), kOneJointUnsized, 1.0);
  CHECK(unsized.motion.local(0, 0) == Approx(0.0 + 9.0 - 2.5));
  // The reference's own posture changes nothing.
  const RegisteredMotion same = register_posture_only(reference, contacts_marked(6, 1.0),
                                                      take_posture(reference.local, TakeCycles()), TakeCycles(), {true}, 1.0);
  CHECK(same.motion.local.isApprox(reference.local));
  CHECK_THROWS_AS(register_posture_only(reference, contacts_marked(6, 1.0), posture, TakeCycles(), {true}, 0.0),
                  InputError);
}

TEST_CASE("posture registration: a walk's style put on a standing take moves only its posture", "[shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  // Mannequiny's idle stands; matched by DTW to the walks' steps, the transfer slid its feet 54
  // times as fast as the idle's and moved a toe 38 times as fast as its fastest joint.
  const auto load = [](const std::string& name) {
    return std::make_shared<const Clip>(read_motion_file(test::shared_motion(name)));
  };
  const auto idle = load("wild/gltf_mannequiny_run.glb");
  const auto neutral = load("bandai_walk_normal.bvh"), style = load("bandai_walk_old.bvh");
  const auto p = prepare_takes(std::vector<std::shared_ptr<const Clip>>{idle, neutral, style}, PrepareOptions());
  REQUIRE(p->takes[0].cycles.kind == CycleKind::kNone);
  for (int i = 1; i < 3; ++i) {
    CHECK(p->takes[static_cast<size_t>(i)].registration.posture_only());
    CHECK(p->takes[static_cast<size_t>(i)].alignment.whole_because.empty());
  }
  const Clip out = test::transfer_on_content(idle, neutral, style, 1.0);
  CHECK(test::fastest_joint_step(out) <= 1.25 * test::fastest_joint_step(*idle));
  // The posture does change: the old walk's stoop.
  CHECK((joint_positions(out) - joint_positions(*idle)).cwiseAbs().maxCoeff() > 0.02 * guess_units(*idle).height);
}

TEST_CASE("cycle extension: a reference laid on more slots plays its last cycles again before its stop, worked by hand") {
  // 60 frames, cycles 10-25 and 25-40, a stop 40-60; on 4 slots: its own two, then both again.
  const CanonicalMotion m = ramp_motion(60, 1.0);
  const TakeCycles c = gait({{10, 25}, {25, 40}}, 0, 15);
  const RegisteredMotion r = extend_by_cycles(m, contacts_marked(60, 1.0), c, 4);
  const CycleRegistration& g = r.registration;
  CHECK(g.pairs == std::vector<int>{0, 1, 0, 1});
  REQUIRE(r.motion.local.rows() == 60 + 15 + 15);
  REQUIRE(g.cycles.cycles.size() == 4);
  CHECK(g.cycles.cycles[2].begin == 40);
  CHECK(g.cycles.cycles[3].begin == 55);
  CHECK(g.cycles.cycles[3].end == 70);
  // Its own frames up to its last cycle's end, as they are.
  for (int v = 0; v < 40; ++v) {
    CHECK(r.motion.local(v, 0) == Approx(v));
    CHECK(g.source[v] == v);
  }
  // The first replay (its cycle 0, 10-25) after its cycle 1 ended on frame 40: the seam (40 - 10)
  // spread over the replay, full at its start; its first frame shows the pose it goes on from.
  CHECK(r.motion.local(40, 0) == Approx(40.0));
  CHECK(g.source[40] == 40.0);
  CHECK(r.motion.local(45, 0) == Approx(15.0 + 30.0 * (1.0 - 5.0 / 15.0)));
  CHECK(g.source[45] == 15.0);
  CHECK(g.source_cycle[45] == 0);
  // The second replay (its cycle 1, 25-40) follows cycle 0 on directly: no seam.
  CHECK(r.motion.local(55, 0) == Approx(25.0));
  CHECK(g.source_cycle[60] == 1);
  // Then its stop, its own frames: the last replay ended on frame 40, where the stop begins.
  for (int f = 40; f < 60; ++f) CHECK(r.motion.local(f + 30, 0) == Approx(f));
  CHECK(g.source[89] == 59.0);
  // The root walks on through the replays: one unit a frame along +z from the first frame's.
  CHECK(r.motion.ground(89, 1) == Approx(89.0));
  // A replay slot count not above the cycles is refused.
  CHECK_THROWS_AS(extend_by_cycles(m, contacts_marked(60, 1.0), c, 2), InputError);
}
