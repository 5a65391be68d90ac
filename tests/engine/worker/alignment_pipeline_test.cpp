// Time alignment through the whole pipeline on the bundled takes: no pops, timing
// blended with alpha, alpha 0 is A on A's matched range, standing at the ends left out, loops.
// The takes are in assets/, so these always run.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "engine/align/time_warp.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/io/motion_file.h"
#include "engine/base/clip.h"
#include "engine/kinematics/units.h"
#include "tests/engine/worker/blend_at.h"
#include "tests/test_data.h"

using namespace mostyle;
using mostyle::test::blend_at;

namespace {

// Acceptance bounds.
constexpr double kPopRatio = 1.25;         // blend's fastest joint (99.9th percentile) vs the takes' fastest
constexpr double kPopPercentile = 0.999;
constexpr double kAlphaZeroMean = 0.03;    // alpha 0 against A at the same source frames, of height
constexpr double kLengthSlack = 1.0;       // frames: a blend at alpha 0 or 1 vs the matched range
constexpr double kPadSeconds = 2.0;        // standing added before and after a take
constexpr int kPadSlack = 10;              // working-rate frames the match may reach into it
constexpr double kSeamRatio = 1.5;         // loop seam vs the largest joint move inside the loop

std::shared_ptr<const Clip> load(const std::string& name) {
  return std::make_shared<const Clip>(read_bvh_file(test::asset("motions/" + name)));
}

// Per frame t >= 1: the largest distance a joint moves from frame t - 1 (F - 1 values).
Eigen::VectorXd joint_speeds(const Eigen::MatrixXd& world) {
  const Eigen::Index joints = world.cols() / 3;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(std::max<Eigen::Index>(0, world.rows() - 1));
  for (Eigen::Index t = 1; t < world.rows(); ++t)
    for (Eigen::Index j = 0; j < joints; ++j)
      v[t - 1] = std::max(v[t - 1], (world.block<1, 3>(t, 3 * j) - world.block<1, 3>(t - 1, 3 * j)).norm());
  return v;
}

// Nearest-rank percentile, q in (0, 1].
double percentile(Eigen::VectorXd v, double q) {
  REQUIRE(v.size() > 0);
  std::sort(v.data(), v.data() + v.size());
  const Eigen::Index rank = static_cast<Eigen::Index>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::clamp<Eigen::Index>(rank - 1, 0, v.size() - 1)];
}

// Mean joint distance between two F x 3M matrices.
double mean_joint_distance(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) {
  REQUIRE(x.rows() == y.rows());
  REQUIRE(x.cols() == y.cols());
  const Eigen::Index joints = x.cols() / 3;
  double sum = 0.0;
  for (Eigen::Index t = 0; t < x.rows(); ++t)
    for (Eigen::Index j = 0; j < joints; ++j) sum += (x.block<1, 3>(t, 3 * j) - y.block<1, 3>(t, 3 * j)).norm();
  return sum / static_cast<double>(x.rows() * joints);
}

bool non_decreasing(const Eigen::VectorXd& v) {
  for (Eigen::Index k = 1; k < v.size(); ++k)
    if (v[k] < v[k - 1]) return false;
  return true;
}

// The clip with its first frame repeated `frames` times before and its last after: standing still
// before and after the take.
Clip padded(const Clip& clip, int frames) {
  Clip out = clip;
  const int n = clip.frames();
  out.motion.resize(n + 2 * frames, clip.motion.cols());
  for (int f = 0; f < frames; ++f) {
    out.motion.row(f) = clip.motion.row(0);
    out.motion.row(frames + n + f) = clip.motion.row(n - 1);
  }
  out.motion.middleRows(frames, n) = clip.motion;
  out.source = clip.source + " (padded)";
  return out;
}

constexpr double kHalfLengthSlack = 1.05;

struct Pair {
  std::shared_ptr<const Clip> a, b;
  std::shared_ptr<const PreparedTakes> p;
  std::shared_ptr<const Decomposed> d;
  double height = 0;
  // A as its file has it (its own frames, prepared with itself): the pair's reference holds its
  // cycles again where B has more (cycle_slots.h), and its world goes on from them.
  Eigen::MatrixXd a_world;
  // A's file frames at an output's reference sources.
  Eigen::VectorXd a_frames(const Eigen::VectorXd& sources) const { return frames_in_take(p->reference(), sources); }
  Eigen::MatrixXd a_at(const Eigen::VectorXd& sources) const { return sample_rows(a_world, a_frames(sources)); }
};

Pair happy_marching() {
  Pair pair;
  pair.a = load("cmu142_walk_happy.bvh");
  pair.b = load("cmu142_walk_marching.bvh");
  pair.p = prepare_takes({pair.a, pair.b}, {});
  pair.d = decompose_takes(*pair.p, DecomposeParams());
  pair.a_world = prepare_takes({pair.a, pair.a}, {})->takes[0].world;
  pair.height = guess_units(*pair.a).height;
  return pair;
}

}  // namespace

TEST_CASE("alignment pipeline: the blend's sources run forward within the matched ranges", "[alignment]") {
  const Pair x = happy_marching();
  const PreparedTakes& p = *x.p;
  const Alignment& al = p.takes[1].alignment;
  INFO("A " << al.a_first << ".." << al.a_last << " of " << p.takes[0].world.rows() << ", B " << al.b_first << ".."
            << al.b_last << " of " << p.takes[1].world.rows() << ", " << p.samples() << " samples");
  CHECK(al.a_first >= 0);
  CHECK(al.a_last < p.takes[0].world.rows());
  CHECK(al.b_first >= 0);
  CHECK(al.b_last < p.takes[1].world.rows());
  CHECK(al.feature.on == AlignOn::kLeftFoot);  // two walks
  CHECK(p.takes[0].x.rows() == p.samples());
  CHECK(p.takes[1].ground.rows() == p.samples());
  CHECK(p.takes[1].contacts.rows() == p.samples());
  for (double alpha : {0.0, 0.5, 1.0}) {
    INFO("alpha " << alpha);
    const MixResult r = blend_at(p, *x.d, alpha);
    REQUIRE(r.sources.col(0).size() == r.motion.world.rows());
    REQUIRE(r.sources.col(1).size() == r.motion.world.rows());
    REQUIRE(r.sample.size() == r.motion.world.rows());
    CHECK(non_decreasing(r.sample));
    CHECK(non_decreasing(r.sources.col(0)));
    CHECK(non_decreasing(r.sources.col(1)));
    CHECK(r.sources.col(0).minCoeff() >= al.a_first - 1e-9);
    CHECK(r.sources.col(0).maxCoeff() <= al.a_last + 1e-9);
    CHECK(r.sources.col(1).minCoeff() >= al.b_first - 1e-9);
    CHECK(r.sources.col(1).maxCoeff() <= al.b_last + 1e-9);
    CHECK(r.motion.contacts.rows() == r.motion.world.rows());
    CHECK(r.motion.world.allFinite());
  }
}

TEST_CASE("alignment pipeline: no pops at alpha 0, 0.5 and 1", "[alignment]") {
  const Pair x = happy_marching();
  const PreparedTakes& p = *x.p;
  const double takes = std::max(joint_speeds(p.takes[0].world).maxCoeff(), joint_speeds(p.takes[1].world).maxCoeff());
  for (double alpha : {0.0, 0.5, 1.0}) {
    const MixResult r = blend_at(p, *x.d, alpha);
    const Eigen::VectorXd speeds = joint_speeds(r.motion.world);
    const double blend = percentile(speeds, kPopPercentile);
    INFO("alpha " << alpha << ": blend's fastest joint move " << blend << " (max " << speeds.maxCoeff()
                  << "), the takes' " << takes << ", " << 100 * blend / x.height << "% of height per frame");
    CHECK(blend <= kPopRatio * takes);
  }
}

TEST_CASE("alignment pipeline: alpha 0 is as long as A's matched range, alpha 1 as B's", "[alignment]") {
  const Pair x = happy_marching();
  const PreparedTakes& p = *x.p;
  const Alignment& al = p.takes[1].alignment;
  // A's range in its file's frames (its own timeline holds replays of its cycles where B has more).
  const Eigen::VectorXd a_ends = x.a_frames(Eigen::Vector2d(al.a_first, al.a_last));
  const double range_a = a_ends[1] - a_ends[0] + 1, range_b = al.b_last - al.b_first + 1;
  const MixResult r0 = blend_at(p, *x.d, 0.0), r1 = blend_at(p, *x.d, 1.0), half = blend_at(p, *x.d, 0.5);
  INFO("A's range " << range_a << ", B's " << range_b << "; frames at alpha 0: " << r0.motion.world.rows() << ", 0.5: "
                    << half.motion.world.rows() << ", 1: " << r1.motion.world.rows());
  CHECK(std::abs(r0.motion.world.rows() - range_a) <= kLengthSlack);
  CHECK(std::abs(r1.motion.world.rows() - range_b) <= kLengthSlack);
  // Half way, as many cycles as half of each take's (17 of A's 15 and B's 19) at the cadence half
  // way between theirs: the length, their product, may run a little past the longer take's.
  CHECK(half.motion.world.rows() >= std::min(r0.motion.world.rows(), r1.motion.world.rows()));
  CHECK(half.motion.world.rows() <= kHalfLengthSlack * std::max(r0.motion.world.rows(), r1.motion.world.rows()));
  // At alpha 0 the output frames are A's own frames, one apart.
  const Eigen::VectorXd own = x.a_frames(r0.sources.col(0));
  for (Eigen::Index k = 1; k < own.size(); ++k) CHECK(own[k] - own[k - 1] == Approx(1.0));
}

TEST_CASE("alignment pipeline: timing_a keeps A's timeline at every alpha", "[alignment]") {
  const Pair x = happy_marching();
  const PreparedTakes& p = *x.p;
  MixParams keep;
  keep.reference_timing = true;
  const MixResult r0 = blend_at(p, *x.d, 0.0, keep), r1 = blend_at(p, *x.d, 1.0, keep);
  INFO("frames at alpha 0: " << r0.motion.world.rows() << ", at 1: " << r1.motion.world.rows());
  CHECK(r0.motion.world.rows() == r1.motion.world.rows());
  CHECK(r0.sources.col(0) == r1.sources.col(0));
  CHECK(r0.motion.world.rows() == blend_at(p, *x.d, 0.0).motion.world.rows());  // alpha 0 is A's timing either way
}

TEST_CASE("alignment pipeline: alpha 0 reproduces A at the frames it shows", "[alignment]") {
  const Pair x = happy_marching();
  const PreparedTakes& p = *x.p;
  for (bool timing_a : {false, true}) {
    MixParams params;
    params.reference_timing = timing_a;
    const MixResult r = blend_at(p, *x.d, 0.0, params);
    const Eigen::MatrixXd a_there = x.a_at(r.sources.col(0));
    const double e = mean_joint_distance(r.motion.world, a_there) / x.height;
    INFO("timing_a " << timing_a << ": mean " << 100 * e << "% of height " << x.height);
    CHECK(e < kAlphaZeroMean);
  }
}

TEST_CASE("alignment pipeline: standing before and after a take is left out of the match", "[alignment]") {
  const Clip happy = read_bvh_file(test::asset("motions/cmu142_walk_happy.bvh"));
  const int pad = static_cast<int>(std::lround(kPadSeconds * happy.fps()));  // 240 frames at 120 fps
  const auto walk = std::make_shared<const Clip>(happy);
  const auto standing = std::make_shared<const Clip>(padded(happy, pad));
  PrepareOptions whole;  // the open-ended alignment of whole takes (by cycles, all of A is covered)
  whole.align.time_base = TimeBase::kWhole;
  SECTION("the padded take as A") {
    const auto p = prepare_takes({standing, walk}, whole);
    const int first = static_cast<int>(std::lround(kPadSeconds * p->fps));  // 60 at 30 fps
    const int last = first + static_cast<int>(p->takes[1].world.rows()) - 1;        // the walk's last frame
    const Alignment& al = p->takes[1].alignment;
    INFO("A (padded, " << p->takes[0].world.rows() << " frames) matched " << al.a_first << ".." << al.a_last
                       << ", walking " << first << ".." << last << "; B matched " << al.b_first << ".." << al.b_last);
    CHECK(std::abs(al.a_first - first) <= kPadSlack);
    CHECK(std::abs(al.a_last - last) <= kPadSlack);
  }
  SECTION("the padded take as B") {
    const auto p = prepare_takes({walk, standing}, whole);
    const int first = static_cast<int>(std::lround(kPadSeconds * p->fps));
    const int last = first + static_cast<int>(p->takes[0].world.rows()) - 1;
    const Alignment& al = p->takes[1].alignment;
    INFO("B (padded, " << p->takes[1].world.rows() << " frames) matched " << al.b_first << ".." << al.b_last
                       << ", walking " << first << ".." << last << "; A matched " << al.a_first << ".." << al.a_last);
    CHECK(std::abs(al.b_first - first) <= kPadSlack);
    CHECK(std::abs(al.b_last - last) <= kPadSlack);
  }
}

TEST_CASE("alignment pipeline: a loop of whole cycles with a seamless seam", "[alignment]") {
  const Pair x = happy_marching();
  const PreparedTakes& p = *x.p;
  MixParams params;
  params.finish.loop = true;
  const MixResult r = blend_at(p, *x.d, 0.5, params);
  const LoopCut& cut = r.motion.loop;
  INFO("loop " << cut.begin << ".." << cut.end << ", " << cut.cycles << " cycles, travel (" << cut.travel.x() << ", "
               << cut.travel.y() << "), turn removed " << cut.turn_removed);
  CHECK(cut.cycles >= 1);
  CHECK(cut.cycles <= kLoopMaxCycles);
  REQUIRE(r.motion.world.rows() == cut.frames());
  CHECK(r.sources.col(0).size() == cut.frames());
  CHECK(r.motion.contacts.rows() == cut.frames());
  // Played on repeat, the next frame after the last is the first moved by the travel per loop.
  const Eigen::Index last = r.motion.world.rows() - 1, joints = r.motion.world.cols() / 3;
  const Eigen::RowVector3d travel(cut.travel.x(), 0.0, cut.travel.y());
  double seam = 0.0;
  for (Eigen::Index j = 0; j < joints; ++j)
    seam = std::max(seam, (r.motion.world.block<1, 3>(0, 3 * j) + travel - r.motion.world.block<1, 3>(last, 3 * j)).norm());
  const double inside = joint_speeds(r.motion.world).maxCoeff();
  INFO("seam move " << seam << ", largest move inside " << inside);
  CHECK(seam <= kSeamRatio * inside);
  // The travel is a walk's: a good part of a body height per cycle.
  CHECK(cut.travel.norm() > 0.2 * x.height * cut.cycles);
}

TEST_CASE("alignment pipeline: with the residuals alpha 0 is A and one alpha per component agrees", "[alignment]") {
  const Pair x = happy_marching();
  const PreparedTakes& p = *x.p;
  MixParams exact;
  exact.finish.foot_lock = false;  // the lock pins planted feet at their mean place, A's own included
  const MixResult r = blend_at(p, *x.d, 0.0, exact);
  const double with_residual = mean_joint_distance(r.motion.world, x.a_at(r.sources.col(0))) / x.height;
  MixParams components = exact;
  components.residual = false;
  const MixResult c = blend_at(p, *x.d, 0.0, components);
  const double components_only = mean_joint_distance(c.motion.world, x.a_at(c.sources.col(0))) / x.height;
  INFO("alpha 0 against A: " << 100 * with_residual << "% of height with residuals, " << 100 * components_only
                             << "% from the components alone");
  // What is left is the sampling of A between its frames along the warp and back (0.1 s of
  // smoothing of the warp moves no frame of A at alpha 0 by more than a fraction of a frame).
  CHECK(with_residual < 0.005);
  CHECK(with_residual < components_only);
  // Per-component alphas all equal to alpha give the single-alpha blend.
  for (double alpha : {0.0, 0.3, 1.0}) {
    const std::vector<double> each(static_cast<size_t>(x.d->components()), alpha);
    const MixResult per = blend_at(p, *x.d, alpha, exact, each), one = blend_at(p, *x.d, alpha, exact);
    REQUIRE(per.motion.world.rows() == one.motion.world.rows());
    CHECK((per.motion.world - one.motion.world).cwiseAbs().maxCoeff() < 1e-9 * x.height);
  }
}

TEST_CASE("alignment pipeline: no pops on the shared motions' hardest pairs, across conventions", "[alignment]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  // The pairs that once popped (turn flips, foot-lock fades, short
  // bones, reconstruction error), both conventions, 30 and 120 fps.
  const std::pair<const char*, const char*> pairs[] = {
      {"bandai_walk_happy.bvh", "cmu142_walk_joy.bvh"},   {"cmu142_walk_joy.bvh", "cmu142_walk_clumsy.bvh"},
      {"cmu142_walk_clumsy.bvh", "bandai_walk_normal.bvh"}, {"bandai_walk_old.bvh", "bandai_walk_proud.bvh"},
      {"cmu142_walk_joy.bvh", "bandai_walk_old.bvh"},     {"bandai_walk_normal.bvh", "cmu142_walk_happy.bvh"},
      {"bandai_walk_normal.bvh", "bandai_walk_tired.bvh"}};
  for (const auto& [name_a, name_b] : pairs) {
    auto a = std::make_shared<const Clip>(read_bvh_file(test::shared_motion(name_a)));
    auto b = std::make_shared<const Clip>(read_bvh_file(test::shared_motion(name_b)));
    const auto p = prepare_takes({a, b}, {});
    const auto d = decompose_takes(*p, DecomposeParams());
    // The pop measure of ../shared/hooks/pop_check.py: 99.9th percentiles, inputs at 30 fps.
    const double takes = std::max(percentile(joint_speeds(p->takes[0].world), kPopPercentile),
                                  percentile(joint_speeds(p->takes[1].world), kPopPercentile));
    for (double alpha : {0.0, 0.5, 1.0}) {
      const double blend = percentile(joint_speeds(blend_at(*p, *d, alpha).motion.world), kPopPercentile);
      INFO(name_a << " + " << name_b << " at alpha " << alpha << ": " << blend / takes << "x the faster take");
      CHECK(blend <= kPopRatio * takes);
    }
  }
}

TEST_CASE("alignment pipeline: a jump on a walking loop gives its posture, and all of the walk plays", "[alignment]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  // Open ends matched 0.6 s of the 2 s loop with the jump and left the rest out; the jump has no
  // steps to match the walk's, so it is laid on all of the walk as its posture.
  auto walk = std::make_shared<const Clip>(read_motion_file(test::shared_motion("wild/gltf_cesiumman_walk.glb")));
  auto jump = std::make_shared<const Clip>(read_motion_file(test::shared_motion("wild/xia_neutral_16.bvh")));
  const auto p = prepare_takes({walk, jump}, {});
  const Alignment& al = p->takes[1].alignment;
  CHECK(p->takes[1].registration.posture_only());
  CHECK(al.a_first == 0);
  CHECK(al.a_last == al.frames_a - 1);
  for (const std::string& w : al.warnings) CHECK(w.find("left out") == std::string::npos);
}

TEST_CASE("alignment pipeline: a walk put on a waving take gives its posture only, as on a standing one",
          "[alignment]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  // The wave repeats (periodic strokes of the left hand) but does not walk: no frame of the walk
  // matches it, and its steps laid on the standing body would slide its feet.
  auto wave = std::make_shared<const Clip>(read_motion_file(test::shared_motion("actions/bandai2_wave-left-hand_active.bvh")));
  auto walk = std::make_shared<const Clip>(read_motion_file(test::shared_motion("bandai_walk_normal.bvh")));
  const auto p = prepare_takes({wave, walk}, {});
  REQUIRE(p->takes[0].cycles.kind == CycleKind::kPeriodic);
  CHECK(p->takes[1].registration.posture_only());
  CHECK(p->takes[1].alignment.a_first == 0);
  CHECK(p->takes[1].alignment.a_last == p->takes[0].canonical.local.rows() - 1);
}

TEST_CASE("alignment pipeline: a take that does not walk gives a walking reference its posture only", "[alignment]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  // A raised hand and a kick have no steps to match a walk's: matched by DTW, the raised hand left
  // out most of the walk; laid on it as a posture, all of the walk plays, moved by the take's mean
  // pose, its arms and head moving as much as the take's.
  auto walk = std::make_shared<const Clip>(read_motion_file(test::shared_motion("bandai_walk_normal.bvh")));
  for (const char* name : {"actions/bandai2_raise-up-right-hand_exhausted.bvh", "actions/bandai_kick_normal.bvh"}) {
    INFO(name);
    auto take = std::make_shared<const Clip>(read_motion_file(test::shared_motion(name)));
    const auto p = prepare_takes({walk, take}, {});
    REQUIRE(p->takes[0].cycles.kind == CycleKind::kGait);
    const PreparedTake& t = p->takes[1];
    CHECK(t.registration.posture_only());
    CHECK(t.alignment.a_first == 0);
    CHECK(t.alignment.a_last == p->takes[0].canonical.local.rows() - 1);
    bool said = false;
    for (const std::string& w : t.alignment.warnings) {
      CHECK(w.find("left out") == std::string::npos);
      said = said || w.find("its posture only") != std::string::npos && w.find("size of its movements") != std::string::npos;
    }
    CHECK(said);
    // Its frames hold the walk's motion, so its feet step with the walk's.
    CHECK(t.own_contacts == p->takes[0].own_contacts);
  }
}

TEST_CASE("alignment pipeline: a walk of more cycles than A plays all of them at alpha 1, A's own at alpha 0", "[alignment]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  // bandai_walk_normal walks 5 gait cycles, bandai_walk_old 7: A's timeline plays its last cycles
  // again for B's last two, and a blend plays as many as its weights give.
  const auto a = std::make_shared<const Clip>(read_bvh_file(test::shared_motion("bandai_walk_normal.bvh")));
  const auto b = std::make_shared<const Clip>(read_bvh_file(test::shared_motion("bandai_walk_old.bvh")));
  const auto p = prepare_takes({a, b}, {});
  const auto d = decompose_takes(*p, DecomposeParams());
  const int cycles_a = static_cast<int>(p->takes[0].cycles.cycles.size());
  const int cycles_b = static_cast<int>(p->takes[1].registration.take_cycles.cycles.size());
  REQUIRE(cycles_b > cycles_a);
  REQUIRE(p->slots.size() == cycles_b);
  const Eigen::Index frames_a = a->frames() * p->fps / a->fps(), frames_b = b->frames() * p->fps / b->fps();
  const MixResult r0 = blend_at(*p, *d, 0.0), r1 = blend_at(*p, *d, 1.0), half = blend_at(*p, *d, 0.5);
  INFO("frames: A " << frames_a << ", B " << frames_b << "; alpha 0 " << r0.motion.world.rows() << ", 0.5 "
                    << half.motion.world.rows() << ", 1 " << r1.motion.world.rows());
  // Alpha 1 is B's whole performance, every frame of it once, in order; alpha 0 A's.
  CHECK(std::abs(r1.motion.world.rows() - frames_b) <= 1);
  CHECK(std::abs(r0.motion.world.rows() - frames_a) <= 1);
  const Eigen::VectorXd own_b = frames_in_take(p->takes[1], r1.sources.col(1));
  const Eigen::VectorXd own_a = frames_in_take(p->takes[0], r0.sources.col(0));
  for (Eigen::Index k = 1; k < own_b.size(); ++k) CHECK(own_b[k] - own_b[k - 1] == Approx(1.0).margin(0.02));
  for (Eigen::Index k = 1; k < own_a.size(); ++k) CHECK(own_a[k] - own_a[k - 1] == Approx(1.0).margin(1e-9));
  CHECK(own_b[own_b.size() - 1] >= frames_b - 2);
  // Half way: a cycle more than A's, and a length between the two.
  CHECK(half.motion.world.rows() > r0.motion.world.rows());
  CHECK(half.motion.world.rows() < r1.motion.world.rows());
  CHECK(half.slot_skips.size() == 1);
  // No pops where a slot is left out: no joint faster than the takes' fastest.
  const double takes = std::max(joint_speeds(p->takes[0].world).maxCoeff(), joint_speeds(p->takes[1].world).maxCoeff());
  CHECK(joint_speeds(half.motion.world).maxCoeff() <= kPopRatio * takes);
}

TEST_CASE("alignment pipeline: a cycle left out of a mix per body part eases each joint's jump as its part is mixed",
          "[alignment]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  // The legs from the old walk (7 cycles), the rest from the normal one (5): the overall weights
  // play one of the two cycles A's timeline plays again, and leave the other out. There each
  // take's pose jumps by a cycle's variation; the legs, all B's, must take B's jump back, not the
  // overall weights' mean of the two takes' jumps.
  const auto a = std::make_shared<const Clip>(read_bvh_file(test::shared_motion("bandai_walk_normal.bvh")));
  const auto b = std::make_shared<const Clip>(read_bvh_file(test::shared_motion("bandai_walk_old.bvh")));
  const auto p = prepare_takes({a, b}, {});
  const auto d = decompose_takes(*p, DecomposeParams());
  std::vector<double> legs_from_b;
  for (const ComponentJoints& c : d->component_joints)
    legs_from_b.push_back(c.region == BodyRegion::kLeftLeg || c.region == BodyRegion::kRightLeg ? 1.0 : 0.0);
  const MixResult m = blend_at(*p, *d, 0.0, {}, legs_from_b);
  REQUIRE(!m.slot_skips.empty());
  // The poses before the clean-up, frame to frame: at a slot left out no joint steps further than
  // it does over the frames on either side.
  for (Eigen::Index k : m.slot_skips) {
    REQUIRE(k >= 4);
    REQUIRE(k + 4 < m.local.rows());
    for (Eigen::Index j = 0; j < m.local.cols() / 3; ++j) {
      auto step = [&](Eigen::Index f) { return (m.local.block(f, 3 * j, 1, 3) - m.local.block(f - 1, 3 * j, 1, 3)).norm(); };
      double around = 0.0;
      for (Eigen::Index f = k - 3; f <= k + 3; ++f)
        if (f != k) around = std::max(around, step(f));
      INFO("frame " << k << ", joint " << j << ": step " << step(k) << ", around " << around);
      CHECK(step(k) <= 1.5 * around);
    }
  }
}
