#include "engine/synthesize/mix_palette.h"
#include "engine/synthesize/mix_measures.h"
#include "engine/measure/fastest_joint.h"
#include "engine/post/speed_limit.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "engine/io/bvh/bvh_read.h"
#include "engine/io/motion_file.h"
#include "engine/kinematics/limb_length.h"
#include "engine/base/error.h"
#include "engine/kinematics/units.h"
#include "engine/prepare/major_skeleton.h"
#include "engine/prepare/major_take.h"
#include "tests/engine/worker/blend_at.h"
#include "tests/test_data.h"

using namespace mostyle;
using mostyle::test::blend_at;

namespace {

constexpr double kExact = 1e-9;        // file units: the same arithmetic, rounding only
constexpr double kSameAsBlend = 0.005;  // mix of two = blend, 0.5% of height
constexpr double kOneHot = 0.02;        // one-hot = blend T1 Ti --alpha 1, 2% of height
constexpr double kStrengthZero = 0.03;  // transfer at strength 0 = content, 3% of height

std::shared_ptr<const Clip> load(const std::string& path) { return std::make_shared<const Clip>(read_bvh_file(path)); }

std::vector<std::shared_ptr<const Clip>> bundled() {
  std::vector<std::shared_ptr<const Clip>> clips;
  for (const char* n : {"cmu142_walk_happy.bvh", "cmu142_walk_marching.bvh", "cmu142_walk_joy.bvh",
                        "cmu142_walk_clumsy.bvh"})
    clips.push_back(load(test::asset(std::string("motions/") + n)));
  return clips;
}

DecomposeParams params() {
  DecomposeParams d;
  d.components = 10;
  return d;
}

// One layer per take at `weights`, per component `component_weights` (k x N) when given.
MixResult mix(const PreparedTakes& p, const Decomposed& d, const std::vector<double>& weights, MixParams params = {},
              const Eigen::MatrixXd& component_weights = Eigen::MatrixXd()) {
  params.layers = take_layers(weights, component_weights);
  MixScratch scratch;
  MixResult out;
  mix_palette(p, d, params, scratch, out);
  return out;
}

// Takes 0 and 1 as `transfer` makes them with no neutral at strength 1: take 1's style on take 0,
// its own neutral, on its timeline and path.
MixResult own_transfer(const PreparedTakes& p) {
  const auto d = decompose_takes(p, params());
  MixParams mp;
  mp.min_weight = transfer_min_weight(1);
  mp.max_weight = transfer_max_weight(1);
  mp.feet_of_reference = true;
  mp.path_leash = transfer_path_leash(TransferNeutral::kContent, false);
  mp.reference_timing = true;  // on the content's timeline, as transfer is
  return mix(p, *d, transfer_weights({1.0}, TransferNeutral::kContent), mp);
}

std::vector<double> one_hot(int n, int i) {
  std::vector<double> w(static_cast<size_t>(n), 0.0);
  w[static_cast<size_t>(i)] = 1.0;
  return w;
}

// Largest joint distance over all frames as a fraction of the height; the frame counts must agree.
double max_distance(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y, double height) {
  REQUIRE(x.rows() == y.rows());
  REQUIRE(x.cols() == y.cols());
  double worst = 0;
  for (Eigen::Index j = 0; j < x.cols() / 3; ++j)
    worst = std::max(worst, (x.middleCols(3 * j, 3) - y.middleCols(3 * j, 3)).rowwise().norm().maxCoeff());
  return worst / height;
}

// The reference and take i prepared as a pair, on the palette's joints.
std::shared_ptr<const PreparedTakes> pair_of(const PreparedTakes& palette, int i) {
  PrepareOptions o;
  o.only_majors = palette.majors;
  return prepare_takes({palette.takes[0].clip, palette.takes[static_cast<size_t>(i)].clip}, o);
}

// A take's canonical pose read at fractional frames of its own.
Eigen::MatrixXd own_pose_at(const PreparedTake& t, const Eigen::VectorXd& frames) {
  RowSampler at;
  at.set(frames, t.canonical.local.rows());
  Eigen::MatrixXd out;
  at.apply(t.canonical.local, out);
  return out;
}

// A difference of poses (K x 3M) with the frames where the mix eases out a cycle slot it left
// out set to 0 (MixResult::slot_skips): there the poses are the takes' own plus the jump eased.
Eigen::MatrixXd outside_eases(const MixResult& m, Eigen::MatrixXd diff) {
  for (Eigen::Index k : m.slot_skips)
    for (Eigen::Index f = k; f < std::min(diff.rows(), k + m.slot_ease); ++f) diff.row(f).setZero();
  return diff;
}

// One-hot mixes of a palette and of a pair may differ by a frame of rounding in the clock (their
// common timelines' samples differ), a frame more for each cycle slot the palette leaves out;
// their common frames are compared.
constexpr Eigen::Index kClockSlackFrames = 1;


}  // namespace

TEST_CASE("palette: two takes with weights 1 - a, a are the pair's blend at alpha a") {
  const auto clips = bundled();
  const auto p = prepare_takes({clips[0], clips[1]}, {});
  const auto d = decompose_takes(*p, params());
  const auto pair_d = decompose_takes(*p, params());
  const double height = guess_units(*clips[0]).height;
  for (double a : {0.0, 0.3, 0.5, 1.0, 1.2}) {
    const MixResult m = mix(*p, *d, {1.0 - a, a});
    const MixResult b = blend_at(*p, *pair_d, a);
    REQUIRE(m.motion.world.rows() == b.motion.world.rows());
    CHECK(max_distance(m.motion.world, b.motion.world, height) < kExact);
    CHECK(max_distance(m.motion.world, b.motion.world, height) < kSameAsBlend);
  }
}

TEST_CASE("palette: four takes, weights checked, one-hot gives the take, equal weights lie among them") {
  const auto clips = bundled();
  const auto p = prepare_takes(clips, {});
  const auto d = decompose_takes(*p, params());
  REQUIRE(p->size() == 4);
  const double height = guess_units(*clips[0]).height;

  SECTION("weights that do not sum to 1, out of range or of takes that are not there are refused") {
    CHECK_THROWS_AS(mix(*p, *d, {0.5, 0.5, 0.5, 0.5}), InputError);
    CHECK_THROWS_AS(mix(*p, *d, {1.6, -0.2, -0.2, -0.2}), InputError);
    CHECK_THROWS_AS(mix(*p, *d, {1.4, -0.6, 0.1, 0.1}), InputError);
    CHECK_THROWS_WITH(mix(*p, *d, {0.2, 0.2, 0.2, 0.2, 0.2}), "expected layers of takes 1 to 4, found one of take 5");
    CHECK_NOTHROW(mix(*p, *d, {0.5, 0.5}));  // the takes without a layer weigh 0
    CHECK_THROWS_AS(mix(*p, *d, {0.5, 0.5, NAN, 0.0}), InputError);
    CHECK_NOTHROW(mix(*p, *d, {1.5, -0.5, 0.0, 0.0}));
    CHECK_NOTHROW(mix(*p, *d, {0.25, 0.25, 0.25, 0.25}));
  }

  SECTION("one-hot weights give each take as its pair's blend at alpha 1 gives it") {
    for (int i = 1; i < 4; ++i) {
      const MixResult m = mix(*p, *d, one_hot(4, i));
      const auto owned = pair_of(*p, i);
      const PreparedTakes& pair = *owned;
      const MixResult b = blend_at(pair, *decompose_takes(pair, params()), 1.0);
      INFO("take " << i);
      REQUIRE(std::abs(m.motion.world.rows() - b.motion.world.rows()) <= kClockSlackFrames);
      // Where the palette has more cycle slots than the pair (another take has more cycles), the
      // one-hot mix leaves this take's replays out, and its clock may then run up to a frame apart
      // from the pair's (a slot's ends lie within a frame of the take's cycles' ends on the smoothed
      // warp): the frames are then the take's own, checked below, not the pair's one by one.
      const Eigen::Index common = std::min(m.motion.world.rows(), b.motion.world.rows());
      if (m.slot_skips.empty()) CHECK(max_distance(m.motion.world.topRows(common), b.motion.world.topRows(common), height) < kOneHot);
      // Before the clean-up, it is the take's own pose at the frames shown.
      CHECK(outside_eases(m, m.local - own_pose_at(p->takes[static_cast<size_t>(i)], m.sources.col(i))).cwiseAbs().maxCoeff() < kExact);
    }
  }

  SECTION("equal weights are the takes' mean pose at the frames each shows") {
    const MixResult m = mix(*p, *d, {0.25, 0.25, 0.25, 0.25});
    Eigen::MatrixXd mean = Eigen::MatrixXd::Zero(m.local.rows(), m.local.cols());
    for (int i = 0; i < 4; ++i) mean += 0.25 * own_pose_at(p->takes[static_cast<size_t>(i)], m.sources.col(i));
    CHECK(outside_eases(m, m.local - mean).cwiseAbs().maxCoeff() < kExact);
    // Its length lies among the takes' lengths over the common stretch.
    double shortest = 1e9, longest = 0;
    for (int i = 0; i < 4; ++i) {
      const Eigen::VectorXd& f = p->timeline.frames[static_cast<size_t>(i)];
      shortest = std::min(shortest, f[f.size() - 1] - f[0]);
      longest = std::max(longest, f[f.size() - 1] - f[0]);
    }
    CHECK(m.motion.world.rows() >= std::floor(shortest));
    CHECK(m.motion.world.rows() <= std::ceil(longest) + 1);
  }

  SECTION("per-part weights: the legs from one take, the rest from another") {
    std::vector<std::pair<BodyPart, std::vector<double>>> given{{BodyPart::kLegs, one_hot(4, 1)}};
    const Eigen::MatrixXd parts = part_weights(given, d->component_joints, one_hot(4, 0));
    const MixResult m = mix(*p, *d, one_hot(4, 0), MixParams(), parts);
    for (size_t c = 0; c < d->component_joints.size(); ++c) {
      const BodyRegion region = d->component_joints[c].region;
      const bool leg = region == BodyRegion::kLeftLeg || region == BodyRegion::kRightLeg;
      CHECK(parts(static_cast<Eigen::Index>(c), 1) == (leg ? 1.0 : 0.0));
    }
    // The ankles follow take 1, the wrists take 0 (closer to it than to take 1).
    const Eigen::MatrixXd take0 = own_pose_at(p->takes[0], m.sources.col(0));
    const Eigen::MatrixXd take1 = own_pose_at(p->takes[1], m.sources.col(1));
    auto distance = [&](const Eigen::MatrixXd& x, MajorJoint joint) {
      const int column = major_column(p->majors, static_cast<int>(joint));
      return (m.local.middleCols(3 * column, 3) - x.middleCols(3 * column, 3)).rowwise().norm().mean();
    };
    CHECK(distance(take1, MajorJoint::kLeftAnkle) < distance(take0, MajorJoint::kLeftAnkle));
    CHECK(distance(take0, MajorJoint::kLeftWrist) < distance(take1, MajorJoint::kLeftWrist));
  }
}

TEST_CASE("palette: transfer identities") {
  const auto clips = bundled();
  const double height = guess_units(*clips[0]).height;
  SECTION("strength 0 is the content take") {
    const auto p = prepare_takes({clips[3], clips[0], clips[1]}, {});
    const auto d = decompose_takes(*p, params());
    MixParams mp;
    mp.min_weight = -kMaxStrength;
    mp.max_weight = kMaxStrength + 1;
    mp.finish.foot_lock = false;  // the lock cleans the content's own sliding (checked below with it on)
    const MixResult m = mix(*p, *d, transfer_weights({0.0}), mp);
    CHECK((m.local - own_pose_at(p->takes[0], m.sources.col(0))).cwiseAbs().maxCoeff() < kExact);
    // In the world, against the content's own positions at the frames shown.
    const Eigen::MatrixXd& world = p->takes[0].world;
    RowSampler at;
    at.set(m.sources.col(0), world.rows());
    Eigen::MatrixXd content;
    at.apply(world, content);
    CHECK(max_distance(m.motion.world, content, height) < kStrengthZero);
    // With the foot lock on, the mean joint distance stays within the bound too.
    mp.finish.foot_lock = true;
    const MixResult locked = mix(*p, *d, transfer_weights({0.0}), mp);
    REQUIRE(locked.motion.world.rows() == content.rows());
    double mean = 0;
    for (Eigen::Index j = 0; j < content.cols() / 3; ++j)
      mean += (locked.motion.world.middleCols(3 * j, 3) - content.middleCols(3 * j, 3)).rowwise().norm().mean();
    CHECK(mean / double(content.cols() / 3) / height < kStrengthZero);
  }
  SECTION("content equal to neutral at strength 1 is the style on the neutral take's path") {
    const auto p = prepare_takes({clips[0], clips[0], clips[1]}, {});
    const auto d = decompose_takes(*p, params());
    MixParams mp;
    mp.min_weight = -kMaxStrength;
    mp.max_weight = kMaxStrength + 1;
    // The foot lock holds a transfer's planted feet to its content's and a blend's to its takes'
    // (here the style's): the identity is the motion's, compared without it.
    mp.finish.foot_lock = false;
    const MixResult m = mix(*p, *d, transfer_weights({1.0}), mp);
    // Content and neutral are one file, aligned onto itself (not exactly frame for frame).
    CHECK((m.local - own_pose_at(p->takes[2], m.sources.col(2))).cwiseAbs().maxCoeff() < 0.01 * height);
    const auto owned = pair_of(*p, 2);
    const PreparedTakes& pair = *owned;
    MixParams unlocked;
    unlocked.finish.foot_lock = false;
    const MixResult b = blend_at(pair, *decompose_takes(pair, params()), 1.0, unlocked);
    REQUIRE(m.motion.world.rows() == b.motion.world.rows());
    CHECK(max_distance(m.motion.world, b.motion.world, height) < kOneHot);
    // Locked, the transfer's planted feet are held to the content's own.
    mp.finish.foot_lock = true;
    const MixResult locked = mix(*p, *d, transfer_weights({1.0}), mp);
    CHECK(locked.foot_sliding_inputs == p->takes[0].planted.speed);
    CHECK(locked.motion.foot_sliding_cleaned <= locked.motion.foot_sliding_raw);
    CHECK(locked.motion.foot_sliding_cleaned <= 1.1 * locked.foot_sliding_inputs);
  }
  SECTION("the content its own neutral: strength 0 is the content, 1 the style on its timeline") {
    const auto p = prepare_takes({clips[3], clips[1]}, {});
    const auto d = decompose_takes(*p, params());
    MixParams mp;
    mp.min_weight = transfer_min_weight(1);
    mp.max_weight = transfer_max_weight(1);
    mp.finish.foot_lock = false;
    const MixResult zero = mix(*p, *d, transfer_weights({0.0}, TransferNeutral::kContent), mp);
    CHECK(outside_eases(zero, zero.local - own_pose_at(p->takes[0], zero.sources.col(0))).cwiseAbs().maxCoeff() < kExact);
    const MixResult one = mix(*p, *d, transfer_weights({1.0}, TransferNeutral::kContent), mp);
    CHECK(outside_eases(one, one.local - own_pose_at(p->takes[1], one.sources.col(1))).cwiseAbs().maxCoeff() < kExact);
  }
  CHECK(transfer_weights({0.5, 0.25}) == std::vector<double>{1.0, -0.75, 0.5, 0.25});
  CHECK(transfer_weights({0.5, 0.25}, TransferNeutral::kContent) == std::vector<double>{0.25, 0.5, 0.25});
  // Every strength at either end keeps every weight within the transfer's range, either way.
  for (double s : {kMinStrength, kMaxStrength})
    for (TransferNeutral neutral : {TransferNeutral::kTake, TransferNeutral::kContent}) {
      MixParams mp;
      mp.layers = transfer_layers(std::vector<double>(4, s), neutral);
      mp.min_weight = transfer_min_weight(4);
      mp.max_weight = transfer_max_weight(4);
      CHECK_NOTHROW(mp.Validate(neutral == TransferNeutral::kTake ? 6 : 5, 0));
    }
  CHECK_THROWS_AS(transfer_weights({}), InputError);
  CHECK_THROWS_AS(transfer_weights({2.5}), InputError);
}

TEST_CASE("palette: components are connected body parts on each convention, and parts map to their joints") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  for (const auto& names : std::vector<std::vector<std::string>>{
           {"bandai_walk_normal.bvh", "bandai_walk_old.bvh", "bandai_walk_happy.bvh"},
           {"cmu142_walk_happy.bvh", "cmu142_walk_marching.bvh", "bandai_walk_proud.bvh"},
           {"bandai_walk_sad.bvh", "cmu142_walk_joy.bvh", "cmu142_walk_clumsy.bvh", "bandai_walk_tired.bvh"}}) {
    std::vector<std::shared_ptr<const Clip>> clips;
    for (const std::string& n : names) clips.push_back(load(test::shared_motion(n)));
    const auto p = prepare_takes(clips, {});
    const auto d = decompose_takes(*p, params());
    INFO(names[0]);
    for (const ComponentJoints& c : d->component_joints) {
      CHECK(connected_in(c.columns, p->parents));
      CHECK(body_region_of(p->majors[static_cast<size_t>(c.centre)]) == c.region);
    }
    // The legs' canonical joints are the hips, knees, ankles and toes of the file's skeleton.
    for (int column = 0; column < static_cast<int>(p->majors.size()); ++column) {
      const BodyRegion region = body_region_of(p->majors[static_cast<size_t>(column)]);
      const std::string& name = p->takes[0].names[static_cast<size_t>(column)];
      if (region == BodyRegion::kLeftLeg) CHECK((name.find("Left") != std::string::npos || name.find("_L") != std::string::npos));
      if (region == BodyRegion::kRightArm)
        CHECK((name.find("Right") != std::string::npos || name.find("_R") != std::string::npos));
    }
    // One-hot on the last take gives its pair's alpha-1 blend.
    const int last = p->size() - 1;
    const MixResult m = mix(*p, *d, one_hot(p->size(), last));
    const auto owned = pair_of(*p, last);
    const PreparedTakes& pair = *owned;
    const MixResult b = blend_at(pair, *decompose_takes(pair, params()), 1.0);
    // Within a frame in length where the palette skips the take's replays (as above), the same
    // frame for frame where it does not.
    REQUIRE(std::abs(m.motion.world.rows() - b.motion.world.rows()) <=
            kClockSlackFrames * (1 + static_cast<Eigen::Index>(m.slot_skips.size())));
    const double height = guess_units(*clips[0]).height;
    if (m.slot_skips.empty()) CHECK(max_distance(m.motion.world, b.motion.world, height) < kOneHot);
    else CHECK(outside_eases(m, m.local - own_pose_at(p->takes[static_cast<size_t>(last)], m.sources.col(last))).cwiseAbs().maxCoeff() < 1e-6 * height);
  }
}

TEST_CASE("palette: a count out of range is refused") {
  const auto clips = bundled();
  CHECK_THROWS_AS(prepare_takes({clips[0]}, {}), InputError);
  std::vector<std::shared_ptr<const Clip>> many(17, clips[0]);
  CHECK_THROWS_AS(prepare_takes(many, {}), InputError);
}

TEST_CASE("palette: weights keyed in time") {
  const auto clips = bundled();
  const double height = guess_units(*clips[0]).height;
  const auto p = prepare_takes({clips[0], clips[1], clips[2]}, {});
  const auto d = decompose_takes(*p, params());
  const std::vector<double> w{0.2, 0.5, 0.3};
  SECTION("keys that all hold one set of weights are those weights") {
    MixParams keyed;
    keyed.keys = {{0.0, w}, {3.0, w}};
    const MixResult a = mix(*p, *d, w), b = mix(*p, *d, w, keyed);
    REQUIRE(a.motion.world.rows() == b.motion.world.rows());
    CHECK(max_distance(a.motion.world, b.motion.world, height) < kExact);
  }
  SECTION("from one take to another: each end as the take's own mix, no joint faster than the two") {
    MixParams keyed;
    keyed.keys = {{1.0, one_hot(3, 0)}, {5.0, one_hot(3, 1)}};
    keyed.finish.foot_lock = false;  // the poses as mixed
    const MixResult m = mix(*p, *d, w, keyed);
    MixParams plain;
    plain.finish.foot_lock = false;
    const MixResult first = mix(*p, *d, one_hot(3, 0), plain);
    // Before the first key: the reference's own mix, frame for frame.
    const Eigen::Index before = static_cast<Eigen::Index>(0.9 * p->fps);
    CHECK(max_distance(m.motion.world.topRows(before), first.motion.world.topRows(before), height) < 1e-6);
    // After the last key, the poses are take 1's at the frames shown.
    const Eigen::Index after = static_cast<Eigen::Index>(5.2 * p->fps);
    REQUIRE(m.local.rows() > after + 10);
    const Eigen::MatrixXd take1 = own_pose_at(p->takes[1], m.sources.col(1));
    CHECK(outside_eases(m, m.local - take1).bottomRows(m.local.rows() - after).cwiseAbs().maxCoeff() < 1e-6 * height);
    // Frame by frame: no joint moves faster than in either take's own mix.
    auto fastest = [&](const Eigen::MatrixXd& x) {
      double v = 0;
      for (Eigen::Index j = 0; j < x.cols() / 3; ++j)
        v = std::max(v, (x.middleCols(3 * j, 3).bottomRows(x.rows() - 1) - x.middleCols(3 * j, 3).topRows(x.rows() - 1))
                            .rowwise()
                            .norm()
                            .maxCoeff());
      return v;
    };
    const MixResult second = mix(*p, *d, one_hot(3, 1), plain);
    CHECK(fastest(m.motion.world) < 1.25 * std::max(fastest(first.motion.world), fastest(second.motion.world)));
  }
  SECTION("keys are refused with per-part weights and with bad times") {
    MixParams keyed;
    keyed.keys = {{0.0, w}};
    CHECK_THROWS_WITH(mix(*p, *d, w, keyed, Eigen::MatrixXd::Constant(d->components(), 3, 1.0 / 3)),
                      Catch::Contains("per-part weights without keys"));
    keyed.keys = {{2.0, w}, {1.0, w}};
    CHECK_THROWS_AS(mix(*p, *d, w, keyed), InputError);
    keyed.keys = {{0.0, {2.0, -0.5, -0.5}}};
    CHECK_THROWS_WITH(mix(*p, *d, w, keyed), Catch::Contains("key 1's weights"));
  }
}

TEST_CASE("palette: a pair of 2.5 s walks loops on one cycle, with a seam no larger than its moves") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  // 75 frames (2.5 s at 30 fps) from a second into each take: about two steps of each foot.
  auto cut = [](const std::string& name) {
    Clip clip = read_bvh_file(test::shared_motion(name));
    Clip out = clip;
    out.motion = clip.motion.middleRows(30, 75);
    out.source = clip.source + " (2.5 s)";
    return std::make_shared<const Clip>(out);
  };
  const auto p = prepare_takes({cut("bandai_walk_normal.bvh"), cut("bandai_walk_tired.bvh")}, {});
  const auto d = decompose_takes(*p, params());
  for (double a : {0.0, 0.5, 1.0}) {
    MixParams looped;
    looped.finish.loop = true;
    const MixResult m = mix(*p, *d, {1.0 - a, a}, looped);
    const LoopCut& loop = m.motion.loop;
    INFO("alpha " << a << ": " << loop.cycles << " cycles, " << loop.frames() << " frames");
    CHECK(loop.cycles >= 1);
    const Eigen::MatrixXd& w = m.motion.world;
    REQUIRE(w.rows() == loop.frames());
    // The seam: the last frame into the first of the next repetition (the first moved by the
    // loop's travel), against the fastest move between two frames inside the loop.
    double inside = 0, seam = 0;
    for (Eigen::Index j = 0; j < w.cols() / 3; ++j) {
      const auto joint = w.middleCols(3 * j, 3);
      inside = std::max(inside, (joint.bottomRows(w.rows() - 1) - joint.topRows(w.rows() - 1)).rowwise().norm().maxCoeff());
      const Eigen::Vector3d next = joint.row(0).transpose() + Eigen::Vector3d(loop.travel.x(), 0.0, loop.travel.y());
      seam = std::max(seam, (next - joint.row(w.rows() - 1).transpose()).norm());
    }
    CHECK(seam <= 1.5 * inside);
  }
}

namespace {

// A mix's planted feet (planted_feet.h) against its takes' own, weighted: the lock never speeds
// them up and holds them within a tenth of the takes'; no joint moves faster than the takes'
// fastest (99.9th percentile of each frame step's fastest joint) within a quarter.
void check_planted_feet(const PreparedTakes& p, const MixResult& m, const std::string& what) {
  auto fastest = [&](const Eigen::MatrixXd& w) {
    std::vector<double> v;
    for (Eigen::Index t = 0; t + 1 < w.rows(); ++t) {
      double step = 0.0;
      for (Eigen::Index c = 0; c + 2 < w.cols(); c += 3)
        step = std::max(step, (w.block<1, 3>(t + 1, c) - w.block<1, 3>(t, c)).norm());
      v.push_back(step * p.fps);
    }
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[std::min(v.size() - 1, static_cast<size_t>(0.999 * static_cast<double>(v.size())))];
  };
  double takes = 0.0;
  for (const PreparedTake& t : p.takes) takes = std::max(takes, fastest(t.world));
  INFO(what << ": planted feet raw " << m.motion.foot_sliding_raw << ", locked " << m.motion.foot_sliding_cleaned
            << ", takes' " << m.foot_sliding_inputs << "; fastest joint " << fastest(m.motion.world) << ", takes' "
            << takes);
  CHECK(m.motion.foot_sliding_cleaned <= m.motion.foot_sliding_raw);
  CHECK(m.motion.foot_sliding_cleaned <= 1.1 * m.foot_sliding_inputs);
  CHECK(fastest(m.motion.world) <= 1.25 * takes);
}

}  // namespace

TEST_CASE("palette: planted feet of a mix and a transfer move as their takes' do") {
  const auto clips = bundled();
  {
    const auto p = prepare_takes(clips, {});
    const auto d = decompose_takes(*p, params());
    const MixResult m = mix(*p, *d, {0.25, 0.25, 0.25, 0.25});
    CHECK(m.foot_sliding_inputs ==
          Approx(0.25 * (p->takes[0].planted.speed + p->takes[1].planted.speed + p->takes[2].planted.speed +
                         p->takes[3].planted.speed)));
    check_planted_feet(*p, m, "a mix of the four bundled takes");
  }
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  auto shared = [](const char* name) { return load(test::shared_motion(name)); };
  {
    const auto p = prepare_takes({shared("bandai_walk_normal.bvh"), shared("bandai_walk_tired.bvh"),
                                  shared("bandai_walk_sad.bvh"), shared("bandai_walk_happy.bvh")},
                                 {});
    const auto d = decompose_takes(*p, params());
    check_planted_feet(*p, mix(*p, *d, {0.25, 0.25, 0.25, 0.25}), "a mix of four Bandai takes");
  }
  {
    // A transfer: measured against its content (a negative weight mixes no takes' feet).
    PrepareOptions own_rate;
    own_rate.fps = 0.0;
    const auto p = prepare_takes({shared("bandai_walk_proud.bvh"), shared("bandai_walk_normal.bvh"),
                                  shared("bandai_walk_old.bvh")},
                                 own_rate);
    const auto d = decompose_takes(*p, params());
    MixParams mp;
    mp.min_weight = -kMaxStrength;
    mp.max_weight = kMaxStrength + 1;
    const MixResult m = mix(*p, *d, transfer_weights({1.0}), mp);
    CHECK(m.foot_sliding_inputs == p->takes[0].planted.speed);
    check_planted_feet(*p, m, "a transfer of a Bandai walk from normal to old");
  }
  if (test::shared_motion("wild/README.md").empty()) return;
  {
    // A one-cycle loop clip (a brisk Mixamo walk) styled by an old walk, its own neutral: the
    // style's short steps under the content's pace slide unless the stride is stretched to it
    // and the lock pins the rest; the lock's seam must not slide the planted feet it pinned
    // (closing it over the whole loop did: 1.15 times as fast after the lock as before).
    const auto p = prepare_takes({std::make_shared<const Clip>(read_motion_file(test::shared_motion("wild/fbx_mixamo_walking.fbx"))),
                                  shared("bandai_walk_old.bvh")},
                                 {});
    REQUIRE(p->takes[0].cycles.loops());
    const MixResult m = own_transfer(*p);
    REQUIRE(m.motion.loop.frames() > 0);
    check_planted_feet(*p, m, "a Mixamo walk loop styled by Bandai old, its own neutral");
  }
  {
    // A short Xia walk, brisker than the style, styled by Bandai old as its own neutral: the
    // style's short steps under the content's pace slide unless the lock pins them, and it can
    // only where the offset between runs changes on the swing's slow steps (spread mid-swing, at
    // the foot's fastest, the speed limit left it no room: 2.5 times the content's).
    const auto p = prepare_takes({shared("wild/xia_old_13.bvh"), shared("bandai_walk_old.bvh")}, {});
    const MixResult m = own_transfer(*p);
    CHECK(m.foot_sliding_inputs == p->takes[0].planted.speed);
    check_planted_feet(*p, m, "a Xia walk styled by Bandai old, its own neutral");
  }
  {
    // A toeless rig (Aalto: ankles only): the toe it lacks has no height, which must not read as
    // a foot the content holds on the floor (it did: each leg pinned over the whole take as one
    // run, its ankle dragged up to a third of the body's height, 1.20 times the content's).
    const auto p = prepare_takes({shared("wild/aalto_k_walk_fast.bvh"), shared("wild/aalto_k_walk_slow.bvh")}, {});
    REQUIRE(p->feet.legs[0].toe < 0);
    check_planted_feet(*p, own_transfer(*p),
                       "a fast Aalto walk styled by a slow one, its own neutral");
  }
}

TEST_CASE("palette: the result's fastest joint, after the clean-up, against the fastest of the takes mixed") {
  const auto clips = bundled();
  const auto p = prepare_takes(clips, {});
  const auto d = decompose_takes(*p, params());
  double fastest = 0.0;
  for (const PreparedTake& t : p->takes) fastest = std::max(fastest, t.fastest_joint);
  const MixResult all = mix(*p, *d, {0.25, 0.25, 0.25, 0.25});
  CHECK(all.fastest_inputs == fastest);
  CHECK(all.motion.fastest_joint == fastest_joint_speed(all.motion.world, p->fps));
  // One take with a weight: the others' joints are not what its joints are held to.
  const MixResult one = mix(*p, *d, one_hot(4, 2));
  CHECK(one.fastest_inputs == p->takes[2].fastest_joint);
  // The report every tool shows: the same numbers, the ratios between them.
  const MixMeasures m = mix_measures(*p, d.get(), &all);
  REQUIRE(m.takes.size() == 4);
  REQUIRE(m.result);
  CHECK(m.body_height == p->feet.body_height);
  for (size_t i = 0; i < 4; ++i) {
    REQUIRE(m.takes[i].fit_error);
    CHECK(*m.takes[i].fit_error == d->rmse[i]);
    CHECK(m.takes[i].planted_speed == p->takes[i].planted.speed);
    CHECK(m.takes[i].fastest_joint == p->takes[i].fastest_joint);
  }
  CHECK(*m.result->fastest_ratio() == Approx(all.motion.fastest_joint / fastest));
  CHECK(*m.result->fastest_ratio() <= kSpeedLimitOverTakes * 1.01);  // no pops
  CHECK(*m.result->planted_ratio() == Approx(all.motion.foot_sliding_cleaned / all.foot_sliding_inputs));
  // Without a result (or a preview not finished), the takes' alone; without a decomposition, no fit.
  CHECK_FALSE(mix_measures(*p, d.get(), &all, false).result);
  const MixMeasures takes_only = mix_measures(*p, nullptr, nullptr);
  CHECK_FALSE(takes_only.result);
  CHECK_FALSE(takes_only.takes[0].fit_error);
  // Still takes: no ratio, not a division by zero.
  ResultMeasures still;
  CHECK_FALSE(still.fastest_ratio());
  CHECK_FALSE(still.planted_ratio());
}

TEST_CASE("palette: strength 0 gives back takes whose bones stretch, and loop clips, feet lock on") {
  if (test::shared_motion("wild/README.md").empty()) {
    WARN("skipped: ../shared/motions/wild is absent");
    return;
  }
  const auto clips = bundled();
  // The robot's thighs are scaled over its run (0.19 to 0.40 long); the Mixamo walk is a loop
  // whose last frame shows its first again.
  for (const char* name : {"gltf_godot_robot_walk_run.glb#run", "fbx_mixamo_walking.fbx"}) {
    INFO(name);
    const auto content = std::make_shared<const Clip>(read_motion_file(test::shared_motion("wild/") + name));
    const auto p = prepare_takes({content, clips[0], clips[1]}, {});
    // The prepared content is in its own mean bone lengths, as every output is.
    const std::vector<double> lengths = bone_lengths(p->takes[0].world, p->parents);
    for (size_t j = 0; j < lengths.size(); ++j) CHECK(std::abs(lengths[j] - p->lengths[j]) < 1e-9);
    const auto d = decompose_takes(*p, params());
    MixParams mp;
    mp.min_weight = -kMaxStrength;
    mp.max_weight = kMaxStrength + 1;
    mp.feet_of_reference = true;
    const MixResult m = mix(*p, *d, transfer_weights({0.0}), mp);
    // Its planted feet measured as its outputs are: the lock has nothing to take out.
    CHECK(m.motion.foot_sliding_raw == Approx(m.foot_sliding_inputs).epsilon(0.01));
    RowSampler at;
    at.set(m.sources.col(0), p->takes[0].world.rows());
    Eigen::MatrixXd own;
    at.apply(p->takes[0].world, own);
    const double height = p->feet.body_height;
    // A loop clip's own seam (its last pose against its first, as the body holds them) is spread
    // over the loop to close it (loop.h close_loop): that much, and no more, may move.
    const PreparedTake& c = p->takes[0];
    REQUIRE(c.cycles.loops());
    const Eigen::VectorXd seam = c.own_local_t.col(c.cycles.loop_frames) - c.own_local_t.col(0);
    double worst_seam = 0.0;
    for (Eigen::Index j = 0; j < seam.size() / 3; ++j) worst_seam = std::max(worst_seam, seam.segment(3 * j, 3).norm());
    INFO("the clip's own seam: " << worst_seam / height << " of the body's height");
    // The frames that show the clip's own (a loop's output goes on past its end, the clip played
    // again from its start moved on by its travel; a clip without its first pose again at its
    // end is given that frame, not compared here).
    const double last = double(c.cycles.loop_frames - 1);
    double worst = 0.0;
    for (Eigen::Index t = 0; t < own.rows(); ++t) {
      if (m.sources(t, 0) > last) continue;
      for (Eigen::Index j = 0; j < own.cols() / 3; ++j)
        worst = std::max(worst, (m.motion.world.block(t, 3 * j, 1, 3) - own.block(t, 3 * j, 1, 3)).norm() / height);
    }
    CHECK(worst < 0.01 + worst_seam / height);
  }
}

namespace {

// Every value of two mixes equal, bit for bit.
void check_same_mix(const MixResult& a, const MixResult& b) {
  CHECK(a.motion.world == b.motion.world);
  CHECK(a.motion.contacts == b.motion.contacts);
  CHECK(a.motion.loop.begin == b.motion.loop.begin);
  CHECK(a.motion.loop.end == b.motion.loop.end);
  CHECK(a.motion.limb_length_max_error == b.motion.limb_length_max_error);
  CHECK(a.motion.foot_sliding_raw == b.motion.foot_sliding_raw);
  CHECK(a.motion.foot_sliding_cleaned == b.motion.foot_sliding_cleaned);
  CHECK(a.local == b.local);
  CHECK(a.sample == b.sample);
  CHECK(a.sources == b.sources);
  CHECK(a.first_sample == b.first_sample);
  CHECK(a.last_sample == b.last_sample);
  CHECK(a.foot_sliding_inputs == b.foot_sliding_inputs);
}

}  // namespace

TEST_CASE("palette: a preview then finish_mix_palette is the whole mix, exactly", "[palette]") {
  const auto clips = bundled();
  const auto p = prepare_takes(clips, {});
  const auto d = decompose_takes(*p, params());
  const std::vector<double> w{0.4, 0.3, 0.2, 0.1};
  std::vector<std::pair<std::string, MixParams>> cases;
  MixParams plain;
  plain.layers = take_layers(w);
  cases.emplace_back("plain", plain);
  MixParams keyed = plain;
  keyed.keys = {{1.0, one_hot(4, 0)}, {4.0, w}};
  cases.emplace_back("keyed", keyed);
  MixParams parts = plain;
  const std::vector<std::pair<BodyPart, std::vector<double>>> legs{{BodyPart::kLegs, one_hot(4, 2)}};
  parts.layers = take_layers(w, part_weights(legs, d->component_joints, w));
  cases.emplace_back("per part", parts);
  MixParams reference = plain;
  reference.reference_timing = true;
  cases.emplace_back("reference timing", reference);
  MixParams loop = plain;
  loop.finish.loop = true;
  cases.emplace_back("loop", loop);
  MixParams unlocked = plain;
  unlocked.finish.foot_lock = false;
  cases.emplace_back("no foot lock", unlocked);
  MixParams feet = plain;
  feet.layers = take_layers({1.0, -0.5, 0.5, 0.0});
  feet.min_weight = transfer_min_weight(1);
  feet.max_weight = transfer_max_weight(1);
  feet.feet_of_reference = true;
  cases.emplace_back("transfer's feet", feet);
  MixScratch shared_scratch;  // one scratch across the cases, as the editor keeps one
  for (const auto& c : cases) {
    INFO(c.first);
    MixScratch scratch;
    MixResult whole;
    mix_palette(*p, *d, c.second, scratch, whole);
    if (c.second.finish.loop) CHECK(whole.motion.loop.frames() > 0);
    MixParams preview = c.second;
    preview.preview = true;
    MixResult staged;
    mix_palette(*p, *d, preview, shared_scratch, staged);
    CHECK(staged.motion.foot_sliding_cleaned == 0.0);
    CHECK(staged.local == whole.local);  // the poses are the preview's already
    CHECK(staged.motion.loop.begin == whole.motion.loop.begin);
    finish_mix_palette(*p, preview, shared_scratch, staged);
    check_same_mix(staged, whole);
    // Completed once: a second call changes nothing.
    const Eigen::MatrixXd world = staged.motion.world;
    finish_mix_palette(*p, preview, shared_scratch, staged);
    CHECK(staged.motion.world == world);
  }
}
