#include "engine/post/foot_lock.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <vector>

#include "engine/base/error.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/kinematics/limb_length.h"
#include "engine/measure/planted_feet.h"
#include "tests/engine/worker/blend_at.h"
#include "tests/engine/two_leg_walk.h"
#include "tests/test_data.h"

using namespace mostyle;
using namespace mostyle::test;

namespace {

constexpr double kExact = 1e-9;   // file units (cm here): IK and locks hold to rounding

}  // namespace

TEST_CASE("the foot lock removes sliding on a skating foot and leaves swing alone", "[foot_lock]") {
  const FootRig rig = test_rig();
  Eigen::MatrixXd planted;
  const Eigen::MatrixXd skating = walk(150, 20.0, &planted);
  Eigen::MatrixXd w = skating;
  FootLockScratch scratch;
  apply_foot_lock(w, rig, scratch);
  CHECK(stance_speed(skating, planted, rig) == Approx(20.0));
  CHECK(stance_speed(w, planted, rig) < kExact);
  // Every step the measure calls planted is pinned too (the swing's ends within 5.1 cm of the
  // floor): the measure drops to rounding.
  CHECK(planted_speed(skating, rig).speed > 20.0);
  CHECK(planted_speed(w, rig).speed < kExact);
  // The lock pins over the contacts and the measure's planted frames.
  Eigen::MatrixXd heights_planted;
  std::vector<double> heights;
  planted_frames(skating, rig, heights_planted, heights);
  Eigen::MatrixXd pinned = planted;
  for (int f = 0; f < 150; ++f)
    for (int side = 0; side < 2; ++side)
      if (heights_planted(f, 2 * side) > 0.5 || heights_planted(f, 2 * side + 1) > 0.5) pinned(f, side) = 1.0;
  const int fade = rig.blend_frames();
  for (int side = 0; side < 2; ++side) {
    const LegColumns& leg = rig.legs[side];
    for (int f = 0; f < 150; ++f) {
      // Hips never move; bone lengths and the foot (ankle to toe) are kept.
      CHECK(at(w, f, leg.hip) == at(skating, f, leg.hip));
      CHECK((at(w, f, leg.knee) - at(w, f, leg.hip)).norm() == Approx(kThigh).epsilon(1e-12));
      CHECK((at(w, f, leg.ankle) - at(w, f, leg.knee)).norm() == Approx(kShin).epsilon(1e-12));
      CHECK((at(w, f, leg.toe) - at(w, f, leg.ankle) - Eigen::Vector3d(12, -6, 0)).norm() < kExact);
      // Heights are the blend's own.
      CHECK(w(f, 3 * leg.ankle + 1) == Approx(skating(f, 3 * leg.ankle + 1)).margin(kExact));
      // Between contacts the swing carries the change of offset from one pin to the next; only
      // frames before the first contact's fade or after the last one's stay bit for bit.
      bool contact_up_to = false, contact_from = false;
      for (int g = 0; g <= std::min(149, f + fade); ++g) contact_up_to |= pinned(g, side) > 0.5;
      for (int g = std::max(0, f - fade); g < 150; ++g) contact_from |= pinned(g, side) > 0.5;
      if (!contact_up_to || !contact_from)
        for (int c : {leg.knee, leg.ankle, leg.toe}) CHECK(at(w, f, c) == at(skating, f, c));
    }
  }
  // Fading in and out: the ankle's largest step is not the lock's jump to its target.
  double worst = 0;
  for (int f = 1; f < 150; ++f) worst = std::max(worst, (at(w, f, 2) - at(w, f - 1, 2)).norm());
  double worst_raw = 0;
  for (int f = 1; f < 150; ++f) worst_raw = std::max(worst_raw, (at(skating, f, 2) - at(skating, f - 1, 2)).norm());
  CHECK(worst < 1.5 * worst_raw);
}

TEST_CASE("the foot lock holds a planted foot's heading: a foot that pivots keeps ankle and toe still",
          "[foot_lock]") {
  // Standing, both feet planted throughout; the left foot turns about the point between its ankle
  // and toe (the ankle and toe going opposite ways, as a style's turning legs make a still
  // content's foot pivot), the right stands. An averaged translation would leave each half its move.
  const FootRig rig = test_rig();
  const int frames = 90;
  Eigen::MatrixXd w(frames, 24);
  for (int f = 0; f < frames; ++f)
    for (int side = 0; side < 2; ++side) {
      const double z = side == 0 ? 10.0 : -10.0;
      const double turn = side == 0 ? 0.15 * std::sin(2 * M_PI * f / 45.0) : 0.0;
      const Eigen::Vector3d mid(6.0, 0.0, z), half(6.0 * std::cos(turn), 0.0, 6.0 * std::sin(turn));
      const Eigen::Vector3d ankle = mid - half + Eigen::Vector3d(0, kAnkleHeight, 0), toe = mid + half;
      const Eigen::Vector3d hip(0.0, kHipHeight, z);
      const Eigen::Vector3d d = ankle - hip;
      const double len = d.norm();
      const Eigen::Vector3d n = d / len, bend = (Eigen::Vector3d::UnitX() - n * n.x()).normalized();
      const double along = (kThigh * kThigh - kShin * kShin + len * len) / (2 * len);
      put(w, f, 4 * side, hip);
      put(w, f, 4 * side + 1, hip + n * along + bend * std::sqrt(kThigh * kThigh - along * along));
      put(w, f, 4 * side + 2, ankle);
      put(w, f, 4 * side + 3, toe);
    }
  const Eigen::MatrixXd before = w;
  FootLockScratch scratch;
  apply_foot_lock(w, rig, scratch);
  CHECK(planted_speed(before, rig).speed > 1.0);  // cm/s, the mean over both feet
  CHECK(planted_speed(w, rig).speed < 1e-6);
  for (int f = 0; f < frames; ++f) {
    // The foot keeps its length and its joints their heights; the standing foot is untouched.
    CHECK((at(w, f, 3) - at(w, f, 2)).norm() == Approx((at(before, f, 3) - at(before, f, 2)).norm()));
    CHECK(w(f, 3 * 3 + 1) == Approx(before(f, 3 * 3 + 1)).margin(kExact));
    CHECK(w(f, 3 * 2 + 1) == Approx(before(f, 3 * 2 + 1)).margin(kExact));
    for (int c : {5, 6, 7}) CHECK(at(w, f, c) == at(before, f, c));
  }
}

TEST_CASE("the foot lock keeps the planted feet's expected drift and pins only what moves beyond it",
          "[foot_lock]") {
  const FootRig rig = test_rig();
  Eigen::MatrixXd planted;
  const Eigen::MatrixXd skating = walk(150, 20.0, &planted);
  // Allowed: every planted foot joint moves as it does (the takes slide so themselves): untouched.
  Eigen::MatrixXd drift = Eigen::MatrixXd::Zero(150, 2 * kFootJoints);
  const std::array<int, kFootJoints> columns = foot_joint_columns(rig);
  for (int f = 0; f + 1 < 150; ++f)
    for (int j = 0; j < kFootJoints; ++j) {
      drift(f, 2 * j) = skating(f + 1, 3 * columns[j]) - skating(f, 3 * columns[j]);
      drift(f, 2 * j + 1) = skating(f + 1, 3 * columns[j] + 2) - skating(f, 3 * columns[j] + 2);
    }
  Eigen::MatrixXd w = skating;
  FootLockScratch scratch;
  apply_foot_lock(w, rig, scratch, &drift);
  CHECK((w - skating).cwiseAbs().maxCoeff() < 1e-9);
  // Expected half of it: the other half is pinned (the lock slides the feet at 10 cm/s).
  const Eigen::MatrixXd half = 0.5 * drift;
  w = skating;
  apply_foot_lock(w, rig, scratch, &half);
  CHECK(stance_speed(w, planted, rig) == Approx(10.0).epsilon(0.02));
  CHECK(planted_speed(w, rig).speed == Approx(0.5 * planted_speed(skating, rig).speed).epsilon(0.02));
  // Allowed more than the foot moves: no faster than it did (untouched).
  const Eigen::MatrixXd twice = 2.0 * drift;
  w = skating;
  apply_foot_lock(w, rig, scratch, &twice);
  CHECK((w - skating).cwiseAbs().maxCoeff() < 1e-9);
  // All of it allowed, but the planted feet kept to a third of their speed: a third allowed.
  FootLockLimits third;
  third.planted_speed = planted_speed(skating, rig).speed / 3.0;
  w = skating;
  apply_foot_lock(w, rig, scratch, &drift, third);
  CHECK(planted_speed(w, rig).speed == Approx(third.planted_speed).epsilon(1e-6));
  CHECK(stance_speed(w, planted, rig) == Approx(20.0 / 3.0).epsilon(1e-6));
  // A limit it is under already changes nothing.
  third.planted_speed = 2.0 * planted_speed(skating, rig).speed;
  w = skating;
  apply_foot_lock(w, rig, scratch, &drift, third);
  CHECK((w - skating).cwiseAbs().maxCoeff() < 1e-9);
  // No drift allowed: pinned, as without one.
  const Eigen::MatrixXd none = Eigen::MatrixXd::Zero(150, 2 * kFootJoints);
  w = skating;
  apply_foot_lock(w, rig, scratch, &none);
  CHECK(stance_speed(w, planted, rig) < kExact);
  const Eigen::MatrixXd wrong = Eigen::MatrixXd::Zero(150, 4);
  CHECK_THROWS_AS(apply_foot_lock(w, rig, scratch, &wrong), InputError);
}

TEST_CASE("the foot lock keeps each swing under a speed, pinning the stances beside it in part", "[foot_lock]") {
  const FootRig rig = test_rig();
  Eigen::MatrixXd planted;
  const Eigen::MatrixXd skating = walk(150, 20.0, &planted);
  auto ankle_speed = [&](const Eigen::MatrixXd& w, int f) { return (at(w, f + 1, 2) - at(w, f, 2)).norm() * kFps; };
  double fastest = 0.0;
  for (int f = 0; f + 1 < 150; ++f) fastest = std::max(fastest, ankle_speed(skating, f));
  FootLockScratch scratch;
  Eigen::MatrixXd free = skating;
  apply_foot_lock(free, rig, scratch);  // no limit: pinned, and the swings carry it
  double fastest_free = 0.0;
  for (int f = 0; f + 1 < 150; ++f) fastest_free = std::max(fastest_free, ankle_speed(free, f));
  REQUIRE(fastest_free > 1.05 * fastest);
  // A limit halfway between the walk's own fastest and the unlimited lock's: no step beyond it.
  const double limit = 0.5 * (fastest + fastest_free);
  INFO("fastest ankle: walk " << fastest << ", locked " << fastest_free << " cm/s");
  Eigen::MatrixXd w = skating;
  FootLockLimits limits;
  limits.fastest_joint = limit;
  apply_foot_lock(w, rig, scratch, nullptr, limits);
  for (int f = 0; f + 1 < 150; ++f) {
    INFO("frame " << f);
    CHECK(ankle_speed(w, f) <= limit * (1 + 1e-9));
  }
  // The stances are pinned in part: slower than the walk skates, not held still.
  CHECK(stance_speed(w, planted, rig) < 0.9 * stance_speed(skating, planted, rig));
  CHECK(stance_speed(w, planted, rig) > stance_speed(free, planted, rig) + 1.0);
  CHECK(planted_speed(w, rig).speed <= planted_speed(skating, rig).speed);
}

TEST_CASE("the foot lock moves a stance's pin towards the side with room rather than pin it in part", "[foot_lock]") {
  // The walk cut at frame 138: the left foot's last stance (frames 120-137) runs to the take's
  // end, so after it nothing limits its offset; before it the swing is held to a speed. Centred
  // on the stance, its pin would ask the swing before it for half the stance's slide and be
  // scaled down to what that swing has room for; moved towards the end, it fits whole.
  const FootRig rig = test_rig();
  Eigen::MatrixXd planted_all;
  const Eigen::MatrixXd long_walk = walk(150, 20.0, &planted_all);
  const Eigen::MatrixXd skating = long_walk.topRows(138);
  const Eigen::MatrixXd planted = planted_all.topRows(138);
  REQUIRE(planted(137, 0) == 1.0);
  REQUIRE(planted(119, 0) == 0.0);
  auto ankle_speed = [&](const Eigen::MatrixXd& w, int f) { return (at(w, f + 1, 2) - at(w, f, 2)).norm() * kFps; };
  double fastest = 0.0;
  for (int f = 0; f + 1 < 138; ++f) fastest = std::max(fastest, ankle_speed(skating, f));
  FootLockScratch scratch;
  Eigen::MatrixXd free = skating;
  apply_foot_lock(free, rig, scratch);
  double fastest_free = 0.0;
  for (int f = 0; f + 1 < 138; ++f) fastest_free = std::max(fastest_free, ankle_speed(free, f));
  const double limit = 0.5 * (fastest + fastest_free);
  FootLockLimits limits;
  limits.fastest_joint = limit;
  Eigen::MatrixXd w = skating;
  apply_foot_lock(w, rig, scratch, nullptr, limits);
  double last_run = 0.0;  // the left ankle's travel over its last stance
  for (int f = 120; f < 137; ++f) last_run += std::hypot(w(f + 1, 6) - w(f, 6), w(f + 1, 8) - w(f, 8));
  INFO("last stance: " << last_run << " cm, skating " << 20.0 * 17 / kFps << " cm");
  CHECK(last_run < 1e-6);
  for (int f = 0; f + 1 < 138; ++f) {
    INFO("frame " << f);
    CHECK(ankle_speed(w, f) <= limit * (1 + 1e-9));
  }
}

TEST_CASE("the foot lock's shapes are checked", "[foot_lock]") {
  const FootRig test = test_rig();
  const Eigen::MatrixXd too_narrow = Eigen::MatrixXd::Zero(10, 12);
  const Eigen::MatrixXd w = Eigen::MatrixXd::Zero(10, 24);
  Eigen::MatrixXd m = w;
  FootLockScratch scratch;
  CHECK_THROWS_AS(apply_foot_lock(m, test, scratch, &too_narrow), InputError);  // a drift of 10 x 12
  FootRig no_height = test;
  no_height.body_height = 0.0;
  CHECK_THROWS_AS(apply_foot_lock(m, no_height, scratch), InputError);
}

namespace {

constexpr double kMaxPlantedRatio = 1.1;  // an output's planted feet over its takes', weighted
constexpr double kMaxPopRatio = 1.25;     // an output's fastest joint over its takes'

// The 99.9th percentile over frame steps of the fastest joint's speed, units per second.
double fastest_joint(const Eigen::MatrixXd& world, double fps) {
  std::vector<double> v;
  for (Eigen::Index t = 0; t + 1 < world.rows(); ++t) {
    double m = 0.0;
    for (Eigen::Index c = 0; c + 2 < world.cols(); c += 3) m = std::max(m, (world.block<1, 3>(t + 1, c) - world.block<1, 3>(t, c)).norm());
    v.push_back(m * fps);
  }
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(0.999 * static_cast<double>(v.size())))];
}

constexpr double kUpperBodyTouch = 1e-2;

void check_pipeline_foot_lock(const std::string& path_a, const std::string& path_b) {
  auto a = std::make_shared<const Clip>(read_bvh_file(path_a));
  auto b = std::make_shared<const Clip>(read_bvh_file(path_b));
  const auto p = prepare_takes({a, b}, PrepareOptions{});
  const Eigen::Index frames = p->takes[0].world.rows();
  REQUIRE(p->takes[0].own_contacts.rows() == frames);
  REQUIRE(p->takes[1].own_contacts.rows() == p->takes[1].world.rows());
  REQUIRE(p->takes[0].contacts.rows() == p->samples());  // both carried onto the time warp
  REQUIRE(p->takes[1].contacts.rows() == p->samples());
  // A walk: each foot planted for a good part of the take.
  CHECK(p->takes[0].own_contacts.col(0).mean() > 0.2);
  CHECK(p->takes[0].own_contacts.col(1).mean() > 0.2);
  CHECK(p->takes[0].planted.speed > 0);
  CHECK(p->takes[0].planted.speed == p->takes[0].planted.speed);
  DecomposeParams dp;
  dp.components = 8;
  dp.max_iterations = 30;
  const auto d = decompose_takes(*p, dp);
  MixParams bp;
  test::BlendRun scratch;
  MixResult locked, free;
  test::blend_into(*p, *d, 0.5, bp, scratch, locked);
  bp.finish.foot_lock = false;
  test::blend_into(*p, *d, 0.5, bp, scratch, free);
  INFO(path_a << " / " << path_b << ": sliding A " << p->takes[0].planted.speed << ", B " << p->takes[1].planted.speed
              << ", raw " << locked.motion.foot_sliding_raw << ", cleaned " << locked.motion.foot_sliding_cleaned
              << ", inputs " << locked.foot_sliding_inputs);
  CHECK(free.motion.foot_sliding_cleaned == free.motion.foot_sliding_raw);
  CHECK(locked.motion.foot_sliding_raw == Approx(free.motion.foot_sliding_raw));
  // The measure is the one every take is measured with, on the output as it is.
  CHECK(locked.motion.foot_sliding_cleaned == Approx(planted_speed(locked.motion.world, p->feet).speed));
  CHECK(locked.foot_sliding_inputs == Approx(0.5 * (p->takes[0].planted.speed + p->takes[1].planted.speed)));
  // The lock never speeds planted feet up, and it holds them to what the takes' own planted feet
  // do (an ankle rolls forward through a stance, a toe pushes off), within a tenth.
  CHECK(locked.motion.foot_sliding_cleaned <= locked.motion.foot_sliding_raw);
  CHECK(locked.motion.foot_sliding_cleaned <= kMaxPlantedRatio * locked.foot_sliding_inputs);
  // No pops: the fastest joint (99.9th percentile of each frame's fastest) no faster than the
  // takes' own fastest, within a quarter.
  const double fastest_take = std::max(fastest_joint(p->takes[0].world, p->fps), fastest_joint(p->takes[1].world, p->fps));
  INFO("fastest joint: blend " << fastest_joint(locked.motion.world, p->fps) << ", unlocked "
                               << fastest_joint(free.motion.world, p->fps) << ", takes " << fastest_take);
  CHECK(fastest_joint(locked.motion.world, p->fps) <= kMaxPopRatio * fastest_take);
  // The lock keeps the limb lengths and touches only the legs below the hips.
  CHECK(locked.motion.limb_length_max_error <= 1e-9 * p->feet.leg_length);
  for (size_t c = 0; c < p->majors.size(); ++c) {
    const bool leg = p->majors[c] >= static_cast<int>(MajorJoint::kLeftKnee) &&
                     p->majors[c] != static_cast<int>(MajorJoint::kRightHip);
    // The speed limit after the lock spreads a knee's bend over neighbouring frames of the whole
    // pose where it would pop: the rest of the body moves by no more than a hair.
    if (!leg) CHECK((locked.motion.world.middleCols(3 * c, 3) - free.motion.world.middleCols(3 * c, 3)).cwiseAbs().maxCoeff() <=
                    kUpperBodyTouch * p->feet.leg_length);
  }
}

}  // namespace

TEST_CASE("the pipeline locks planted feet of a real blend (assets, CMU)", "[foot_lock]") {
  check_pipeline_foot_lock(test::asset("motions/cmu142_walk_happy.bvh"), test::asset("motions/cmu142_walk_joy.bvh"));
}

TEST_CASE("the pipeline locks planted feet of real blends from ../shared/motions", "[foot_lock]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  check_pipeline_foot_lock(test::shared_motion("bandai_walk_normal.bvh"), test::shared_motion("bandai_walk_tired.bvh"));
  check_pipeline_foot_lock(test::shared_motion("cmu142_walk_joy.bvh"), test::shared_motion("bandai_walk_sad.bvh"));
}

namespace {

// Standing on nearly straight legs (hip to ankle 0.999 of the leg) while the hips sway +-3 cm
// forwards and back over a second; the feet stand under the hips and so slide with them when
// `skating`, else stay put. Left leg at z -10, right at +10, facing +X.
Eigen::MatrixXd swaying_stance(int frames, bool skating) {
  Eigen::MatrixXd w(frames, 24);
  const double reach = 0.999 * (kThigh + kShin);
  for (int side = 0; side < 2; ++side) {
    const double z = side == 0 ? -10.0 : 10.0;
    for (int f = 0; f < frames; ++f) {
      const double sway = 3.0 * std::sin(2.0 * M_PI * f / kFps);
      const Eigen::Vector3d ankle(skating ? sway : 0.0, kAnkleHeight, z);
      const Eigen::Vector3d hip = ankle + Eigen::Vector3d(skating ? 0.0 : sway, 0.0, 0.0) +
                                  Eigen::Vector3d(0.0, std::sqrt(reach * reach - (skating ? 0.0 : sway * sway)), 0.0);
      // The knee a little forward of the hip-ankle line, the bones their lengths.
      const Eigen::Vector3d d = ankle - hip, n = d.normalized();
      const Eigen::Vector3d bend = (Eigen::Vector3d::UnitX() - n * n.x()).normalized();
      const double along = (kThigh * kThigh - kShin * kShin + d.squaredNorm()) / (2 * d.norm());
      put(w, f, 4 * side, hip);
      put(w, f, 4 * side + 1, hip + n * along + bend * std::sqrt(kThigh * kThigh - along * along));
      put(w, f, 4 * side + 2, ankle);
      put(w, f, 4 * side + 3, ankle + Eigen::Vector3d(12, -6, 0));
    }
  }
  return w;
}

}  // namespace

TEST_CASE("the foot lock brings the body down where straight legs cannot reach the pinned feet", "[foot_lock]") {
  const FootRig rig = test_rig();
  const int frames = 90;
  const Eigen::MatrixXd none = Eigen::MatrixXd::Zero(frames, 2 * kFootJoints);
  FootLockLimits limits;
  limits.planted_speed = 0.01;  // cm/s: the content's own feet stand still
  FootLockScratch scratch;
  // Feet that stand still already: nothing to pin, the body stays (a take alone is left as it is).
  const Eigen::MatrixXd still = swaying_stance(frames, false);
  Eigen::MatrixXd w = still;
  apply_foot_lock(w, rig, scratch, &none, limits);
  CHECK((w - still).cwiseAbs().maxCoeff() < kExact);
  // Feet that slide with the hips: pinning them needs more than straight legs reach, so the body
  // comes down (a few millimetres) and the knees bend; the feet then stand still.
  const Eigen::MatrixXd skating = swaying_stance(frames, true);
  w = skating;
  apply_foot_lock(w, rig, scratch, &none, limits);
  CHECK(planted_speed(skating, rig).speed > 50.0 * limits.planted_speed);
  CHECK(planted_speed(w, rig).speed <= limits.planted_speed);
  double lowest = 0.0, fastest_knee = 0.0;
  for (int f = 0; f < frames; ++f)
    for (int side = 0; side < 2; ++side) {
      const int hip = 4 * side, knee = hip + 1, ankle = hip + 2;
      const double down = skating(f, 3 * hip + 1) - w(f, 3 * hip + 1);
      CHECK(down >= -kExact);
      CHECK(down <= 0.05 * rig.leg_length + kExact);
      lowest = std::max(lowest, down);
      CHECK((at(w, f, knee) - at(w, f, hip)).norm() == Approx(kThigh).epsilon(1e-9));
      CHECK((at(w, f, ankle) - at(w, f, knee)).norm() == Approx(kShin).epsilon(1e-9));
      CHECK(w(f, 3 * ankle + 1) == Approx(kAnkleHeight).epsilon(1e-12));  // heights kept
      if (f > 0) fastest_knee = std::max(fastest_knee, (at(w, f, knee) - at(w, f - 1, knee)).norm());
    }
  CHECK(lowest > 0.0);
  // No pop: the knees move about as fast as the swaying hips (3 cm at 2 pi a second: 0.63 cm a frame).
  CHECK(fastest_knee < 1.5);
}
