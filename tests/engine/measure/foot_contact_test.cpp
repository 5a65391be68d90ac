#include "tests/engine/run/blend_at.h"
#include "engine/measure/foot_contact.h"
#include "engine/measure/planted_feet.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <vector>

#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "engine/kinematics/limb_length.h"
#include "engine/run/blend_params.h"
#include "tests/engine/synthetic_gait.h"
#include "tests/test_data.h"

using namespace mostyle;

namespace {

constexpr double kExact = 1e-9;   // file units (cm here): IK and locks hold to rounding
constexpr double kFps = 30.0;
constexpr double kThigh = 40.0, kShin = 40.0;
constexpr double kHipHeight = 75.0, kAnkleHeight = 8.0;
constexpr double kBodyHeight = 170.0;  // planted within 3% of it (5.1 cm) of a joint's floor
constexpr double kSpeed = 100.0;     // hips, cm/s along +X
constexpr int kCycle = 30;           // frames per step of one foot
constexpr int kStance = 18;          // of which planted

// Columns: left hip, knee, ankle, toe, then the right leg's.
FootRig test_rig() {
  FootRig rig;
  rig.legs[0] = {0, 1, 2, 3};
  rig.legs[1] = {4, 5, 6, 7};
  rig.leg_length = kThigh + kShin;
  rig.body_height = kBodyHeight;
  rig.fps = kFps;
  return rig;
}

// The ankles' mean horizontal speed over the steps where `stance` (F x 2) has the foot down at
// both ends, cm/s: how fast the walk's own stance phases slide.
double stance_speed(const Eigen::MatrixXd& w, const Eigen::MatrixXd& stance, const FootRig& rig) {
  double sum = 0.0;
  int steps = 0;
  for (int side = 0; side < 2; ++side) {
    const int a = rig.legs[side].ankle;
    for (Eigen::Index t = 0; t + 1 < w.rows(); ++t) {
      if (stance(t, side) <= 0.5 || stance(t + 1, side) <= 0.5) continue;
      sum += std::hypot(w(t + 1, 3 * a) - w(t, 3 * a), w(t + 1, 3 * a + 2) - w(t, 3 * a + 2)) * rig.fps;
      ++steps;
    }
  }
  return steps > 0 ? sum / steps : 0.0;
}

Eigen::Vector3d at(const Eigen::MatrixXd& m, Eigen::Index f, int c) { return m.block<1, 3>(f, 3 * c).transpose(); }
void put(Eigen::MatrixXd& m, Eigen::Index f, int c, const Eigen::Vector3d& v) { m.block<1, 3>(f, 3 * c) = v.transpose(); }

// A walk of two legs: hips moving at kSpeed, each foot planted for kStance frames of every
// kCycle (the right half a cycle later), swinging forward with eased motion and a lift in
// between. `skate`: cm/s the planted foot slides forward (a skating blend). The knee bends
// forward (+X) with the thigh and shin lengths fixed; the toe is 12 cm ahead of the ankle.
// planted (out): F x 2, 1 on the planted frames.
Eigen::MatrixXd walk(int frames, double skate, Eigen::MatrixXd* planted) {
  Eigen::MatrixXd w(frames, 24);
  planted->setZero(frames, 2);
  for (int side = 0; side < 2; ++side) {
    const double z = side == 0 ? 10.0 : -10.0;
    const int shift = side == 0 ? 0 : kCycle / 2;
    for (int f = 0; f < frames; ++f) {
      const double t = f / kFps;
      const Eigen::Vector3d hip(kSpeed * t, kHipHeight, z);
      // Phase within this foot's cycle; cycle k plants the foot under mid-stance hips.
      const int g = f + shift;
      const int k = g / kCycle, phase = g % kCycle;
      auto plant_x = [&](int cycle) { return kSpeed * ((cycle * kCycle - shift) + kStance / 2.0) / kFps; };
      Eigen::Vector3d ankle;
      if (phase < kStance) {
        ankle = Eigen::Vector3d(plant_x(k) + skate * (phase - kStance / 2.0) / kFps, kAnkleHeight, z);
        (*planted)(f, side) = 1;
      } else {
        const double u = (phase - kStance + 1.0) / (kCycle - kStance + 1.0);  // (0, 1)
        const double from = plant_x(k) + skate * (kStance / 2.0) / kFps;
        const double to = plant_x(k + 1) - skate * (kStance / 2.0) / kFps;
        const double ease = 0.5 - 0.5 * std::cos(M_PI * u);
        const double lift = 12.0 * std::pow(std::sin(M_PI * u), 2);
        ankle = Eigen::Vector3d(from + (to - from) * ease, kAnkleHeight + lift, z);
      }
      // Knee: law of cosines, bent toward +X.
      const Eigen::Vector3d d = ankle - hip;
      const double len = d.norm();
      const Eigen::Vector3d n = d / len;
      const Eigen::Vector3d bend = (Eigen::Vector3d::UnitX() - n * n.x()).normalized();
      const double along = (kThigh * kThigh - kShin * kShin + len * len) / (2 * len);
      const Eigen::Vector3d knee = hip + n * along + bend * std::sqrt(kThigh * kThigh - along * along);
      const int base = 4 * side;
      put(w, f, base, hip);
      put(w, f, base + 1, knee);
      put(w, f, base + 2, ankle);
      put(w, f, base + 3, ankle + Eigen::Vector3d(12, -6, 0));
    }
  }
  return w;
}

}  // namespace

TEST_CASE("two-bone IK reaches what it can, keeps lengths and the knee's bend", "[foot_contact]") {
  const Eigen::Vector3d hip(0, 80, 0), knee(5, 42, 3), ankle(0, 5, 0);
  const double thigh = (knee - hip).norm(), shin = (ankle - knee).norm();
  const Eigen::Vector3d fallback(1, 0, 0);
  Eigen::Vector3d k, a;
  SECTION("a reachable target") {
    const Eigen::Vector3d target(20, 10, -5);
    two_bone_ik(hip, knee, ankle, target, fallback, &k, &a);
    CHECK((a - target).norm() < kExact);
    CHECK((k - hip).norm() == Approx(thigh).epsilon(1e-12));
    CHECK((a - k).norm() == Approx(shin).epsilon(1e-12));
    // The knee still bends the way it did (toward +X, +Z here).
    const Eigen::Vector3d n = (target - hip).normalized();
    const Eigen::Vector3d old_bend = (knee - hip) - n * n.dot(knee - hip);
    const Eigen::Vector3d new_bend = (k - hip) - n * n.dot(k - hip);
    CHECK(old_bend.dot(new_bend) > 0);
    CHECK(std::abs(old_bend.normalized().cross(new_bend.normalized()).norm()) < 1e-9);
  }
  SECTION("the ankle where it is: nothing moves") {
    two_bone_ik(hip, knee, ankle, ankle, fallback, &k, &a);
    CHECK((a - ankle).norm() < kExact);
    CHECK((k - knee).norm() < kExact);
  }
  SECTION("out of reach: straight leg toward the target") {
    const Eigen::Vector3d target(0, -200, 0);
    two_bone_ik(hip, knee, ankle, target, fallback, &k, &a);
    CHECK((a - hip).norm() == Approx(thigh + shin));
    CHECK((a - hip).normalized().dot(Eigen::Vector3d(0, -1, 0)) == Approx(1.0));
    CHECK((k - hip).norm() == Approx(thigh));
  }
  SECTION("a straight leg bends along the fallback") {
    const Eigen::Vector3d straight_knee(0, 40, 0), straight_ankle(0, 0, 0);
    two_bone_ik(hip, straight_knee, straight_ankle, Eigen::Vector3d(0, 20, 0), fallback, &k, &a);
    CHECK(a.y() == Approx(20.0));
    CHECK(k.x() > 0);  // bent toward the fallback
    CHECK(k.z() == Approx(0.0).margin(1e-12));
  }
}

TEST_CASE("contacts of a synthetic walk are its planted phases", "[foot_contact]") {
  const FootRig rig = test_rig();
  Eigen::MatrixXd planted;
  const Eigen::MatrixXd w = walk(150, 0.0, &planted);
  const Eigen::MatrixXd c = detect_foot_contacts(w, rig);
  REQUIRE(c.rows() == 150);
  REQUIRE(c.cols() == 2);
  // Each frame agrees, but for at most one frame at either end of a contact.
  for (int side = 0; side < 2; ++side) {
    for (int f = 1; f + 1 < 150; ++f) {
      INFO("side " << side << " frame " << f);
      if (planted(f - 1, side) == planted(f, side) && planted(f + 1, side) == planted(f, side))
        CHECK(c(f, side) == planted(f, side));
    }
  }
  CHECK(stance_speed(w, c, rig) < kExact);
  // A foot skating at 20 cm/s (under the speed threshold) is still in contact.
  Eigen::MatrixXd skating_stance;
  const Eigen::MatrixXd skating = walk(150, 20.0, &skating_stance);
  CHECK(detect_foot_contacts(skating, rig).sum() > 0.8 * skating_stance.sum());
}

TEST_CASE("the foot lock removes sliding on a skating foot and leaves swing alone", "[foot_contact]") {
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
          "[foot_contact]") {
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
          "[foot_contact]") {
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

TEST_CASE("the foot lock keeps each swing under a speed, pinning the runs beside it in part", "[foot_contact]") {
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
  // The runs are pinned in part: slower than the walk skates, not held still.
  CHECK(stance_speed(w, planted, rig) < 0.9 * stance_speed(skating, planted, rig));
  CHECK(stance_speed(w, planted, rig) > stance_speed(free, planted, rig) + 1.0);
  CHECK(planted_speed(w, rig).speed <= planted_speed(skating, rig).speed);
}

TEST_CASE("the foot lock moves a run's pin towards the side with room rather than pin it in part", "[foot_contact]") {
  // The walk cut at frame 138: the left foot's last stance (frames 120-137) runs to the take's
  // end, so after it nothing limits its offset; before it the swing is held to a speed. Centred
  // on the run, its pin would ask the swing before it for half the run's slide and be scaled down
  // to what that swing has room for; moved towards the end, it fits whole.
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

TEST_CASE("contacts are tidied as detection tidies them: short breaks filled, short contacts dropped",
          "[foot_contact]") {
  FootRig rig = test_rig();  // 30 fps: breaks of up to 2 frames filled, contacts under 3 frames dropped
  rig.options.min_contact_seconds = 0.1;
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(20, 2);
  c.col(0).segment(2, 5).setOnes();   // 2-6
  c.col(0).segment(8, 6).setOnes();   // 8-13: a break of one frame (7)
  c.col(1).segment(4, 2).setOnes();   // 4-5: too short
  c.col(1).segment(10, 4).setOnes();  // 10-13
  tidy_contacts(c, rig);
  CHECK(c.col(0).segment(2, 12).minCoeff() == 1.0);
  CHECK(c(1, 0) == 0.0);
  CHECK(c(14, 0) == 0.0);
  CHECK(c.col(1).segment(0, 10).maxCoeff() == 0.0);
  CHECK(c.col(1).segment(10, 4).minCoeff() == 1.0);
}

TEST_CASE("tidying keeps contacts cut by the take's ends and rounds the shortest contact to a frame",
          "[foot_contact]") {
  FootRig rig = test_rig();
  rig.options.min_contact_seconds = 0.1;  // 3 frames at 30 fps
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(20, 2);
  c.col(0).head(2).setOnes();   // 0-1: cut by the start
  c.col(0).tail(1).setOnes();   // 19: cut by the end (a landing)
  c.col(1).segment(5, 2).setOnes();  // 5-6: short, inside
  tidy_contacts(c, rig);
  CHECK(c.col(0).head(2).minCoeff() == 1.0);
  CHECK(c(19, 0) == 1.0);
  CHECK(c.col(1).maxCoeff() == 0.0);
  rig.fps = 24.0;  // 0.1 s is 2.4 frames: 2 are enough
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(20, 2);
  d.col(0).segment(5, 2).setOnes();
  d.col(1).segment(9, 1).setOnes();
  tidy_contacts(d, rig);
  CHECK(d.col(0).segment(5, 2).minCoeff() == 1.0);
  CHECK(d.col(1).maxCoeff() == 0.0);
}

namespace {

// 1 where a synthetic gait's foot is planted (test::gait_take), per frame. F x 2.
Eigen::MatrixXd gait_planted(const test::GaitSpec& g, int frames) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(frames, 2);
  for (int f = 0; f < frames; ++f)
    for (int side = 0; side < 2; ++side) {
      const double phase = f / g.fps / g.cycle_s + g.start + (side == 0 || g.together ? 0.0 : 0.5);
      out(f, side) = phase - std::floor(phase) < g.stance ? 1.0 : 0.0;
    }
  return out;
}

// Frames where detected contacts differ from the planted phases, leaving out those within
// `slack` frames of a change of either.
int contact_errors(const Eigen::MatrixXd& detected, const Eigen::MatrixXd& planted, int slack) {
  int errors = 0;
  for (int side = 0; side < 2; ++side)
    for (Eigen::Index f = 0; f < planted.rows(); ++f) {
      bool near_change = false;
      for (Eigen::Index u = std::max<Eigen::Index>(1, f - slack); u <= std::min(planted.rows() - 1, f + slack); ++u)
        near_change = near_change || planted(u, side) != planted(u - 1, side);
      if (!near_change && detected(f, side) != planted(f, side)) ++errors;
    }
  return errors;
}

}  // namespace

TEST_CASE("contacts of a walk in place: the planted foot moves with the belt under still hips", "[foot_contact]") {
  test::GaitSpec g;
  g.in_place = true;
  g.start = 0.3;
  const int frames = 150;
  const Eigen::MatrixXd c = detect_foot_contacts(test::gait_take(g, frames), test::gait_rig(g.fps));
  const Eigen::MatrixXd planted = gait_planted(g, frames);
  CHECK(contact_errors(c, planted, 1) == 0);
  // The same walk travelling is detected the same way (its planted foot is still).
  g.in_place = false;
  CHECK(contact_errors(detect_foot_contacts(test::gait_take(g, frames), test::gait_rig(g.fps)), planted, 1) == 0);
  // A run in place: short contacts, flight phases between them; at 24 fps too.
  for (const double fps : {24.0, 120.0}) {
    test::GaitSpec run;
    run.in_place = true;
    run.fps = fps;
    run.cycle_s = 0.7;
    run.stance = 0.3;
    run.stride = 0.6;
    run.lift = 0.3;
    const int n = static_cast<int>(2.0 * fps);
    INFO(fps << " fps");
    const Eigen::MatrixXd rc = detect_foot_contacts(test::gait_take(run, n), test::gait_rig(fps));
    CHECK(contact_errors(rc, gait_planted(run, n), fps > 100 ? 3 : 1) == 0);
    CHECK(rc.col(0).sum() > 0.5 * gait_planted(run, n).col(0).sum());
  }
}

TEST_CASE("contacts of a loop clip run across its end", "[foot_contact]") {
  test::GaitSpec g;  // one cycle in place, cut while the left foot stands
  g.in_place = true;
  g.start = 0.3;
  const int n = 30;
  const Eigen::MatrixXd world = test::gait_take(g, n);  // frame n would be frame 0 again
  const Eigen::MatrixXd c = detect_foot_contacts(world, test::gait_rig(g.fps), n);
  const Eigen::MatrixXd planted = gait_planted(g, n);
  CHECK(c(0, 0) == 1.0);  // the stance across the end is one contact: both ends of it kept
  CHECK(c(n - 1, 0) == 1.0);
  Eigen::MatrixXd wrapped(n + 2, 2);  // the loop's contacts around its end, to check the changes there
  wrapped << planted.bottomRows(1), planted, planted.topRows(1);
  Eigen::MatrixXd detected(n + 2, 2);
  detected << c.bottomRows(1), c, c.topRows(1);
  CHECK(contact_errors(detected, wrapped, 1) == 0);
  // A loop whose last frame repeats its first: that frame's contacts are frame 0's.
  const Eigen::MatrixXd r = detect_foot_contacts(test::gait_take(g, n + 1), test::gait_rig(g.fps), n);
  CHECK(r.row(n) == r.row(0));
  CHECK(r.topRows(n) == c);
  CHECK_THROWS_AS(detect_foot_contacts(world, test::gait_rig(g.fps), n + 1), InputError);
  CHECK_THROWS_AS(detect_foot_contacts(world, test::gait_rig(g.fps), 1), InputError);
}

TEST_CASE("contacts follow a floor that rises over the take, and a landing in its last frames", "[foot_contact]") {
  test::GaitSpec g;
  const int frames = 240;  // 8 s, the ground rising 0.3 m (a third of the leg)
  Eigen::MatrixXd world = test::gait_take(g, frames);
  for (Eigen::Index f = 0; f < frames; ++f)
    for (Eigen::Index j = 0; j < 9; ++j) world(f, 3 * j + 1) += 0.3 * f / (frames - 1);
  const Eigen::MatrixXd c = detect_foot_contacts(world, test::gait_rig(g.fps));
  CHECK(contact_errors(c, gait_planted(g, frames), 1) == 0);
  // Cut two frames after the left foot touches down (the ankle still slowing): it has landed.
  test::GaitSpec landing;
  landing.start = 0.5;  // the left foot lands at frame 15
  const int n = 15 + 3;
  const Eigen::MatrixXd end = detect_foot_contacts(test::gait_take(landing, n), test::gait_rig(landing.fps));
  CHECK(end(n - 1, 0) == 1.0);
  CHECK(end(n - 4, 0) == 0.0);
}

TEST_CASE("contacts are carried through a warp", "[foot_contact]") {
  Eigen::MatrixXd b(5, 2);
  b << 1, 0, 1, 0, 0, 1, 0, 1, 1, 1;
  Eigen::VectorXd warp(4);
  warp << 0.0, 1.6, 2.4, 4.0;  // rounds to B frames 0, 2, 2, 4
  const Eigen::MatrixXd carried = carry_contacts(b, warp);
  Eigen::MatrixXd expected(4, 2);
  expected << 1, 0, 0, 1, 0, 1, 1, 1;
  CHECK(carried == expected);
}

TEST_CASE("foot contact options and shapes are checked", "[foot_contact]") {
  FootContactOptions o;
  CHECK_NOTHROW(o.Validate());
  o.speed_fraction = -1;
  CHECK_THROWS_AS(o.Validate(), InputError);
  o = FootContactOptions{};
  o.blend_seconds = NAN;
  CHECK_THROWS_AS(o.Validate(), InputError);
  const std::vector<int> majors = {0, 12, 13, 14, 16, 17, 18};
  CHECK_THROWS_AS(make_foot_rig(majors, std::vector<double>(7, 1.0), 0.0), InputError);
  CHECK_THROWS_AS(make_foot_rig(majors, std::vector<double>(6, 1.0), 30.0), InputError);
  const FootRig rig = make_foot_rig(majors, {0, 5, 40, 40, 5, 42, 38}, 30.0);
  CHECK(rig.legs[0].hip == 1);
  CHECK(rig.legs[0].ankle == 3);
  CHECK(rig.legs[0].toe == -1);
  CHECK(rig.legs[1].knee == 5);
  CHECK(rig.leg_length == Approx(80.0));
  CHECK(rig.body_height == Approx(80.0));  // the legs only: this skeleton has no trunk

  const FootRig test = test_rig();
  const Eigen::MatrixXd too_narrow = Eigen::MatrixXd::Zero(10, 12);
  CHECK_THROWS_AS(detect_foot_contacts(too_narrow, test), InputError);
  const Eigen::MatrixXd w = Eigen::MatrixXd::Zero(10, 24);
  Eigen::MatrixXd m = w;
  FootLockScratch scratch;
  CHECK_THROWS_AS(apply_foot_lock(m, test, scratch, &too_narrow), InputError);  // a drift of 10 x 12
  FootRig no_height = test;
  no_height.body_height = 0.0;
  CHECK_THROWS_AS(apply_foot_lock(m, no_height, scratch), InputError);
  CHECK_THROWS_AS(carry_contacts(Eigen::MatrixXd::Zero(0, 2), Eigen::VectorXd::Zero(3)), InputError);
  // No frames: no contacts, no sliding, nothing to lock.
  const Eigen::MatrixXd empty(0, 24);
  CHECK(detect_foot_contacts(empty, test).rows() == 0);
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
  CHECK(take_foot_sliding(*p, 0) > 0);
  CHECK(take_foot_sliding(*p, 0) == p->takes[0].planted.speed);
  DecomposeParams dp;
  dp.components = 8;
  dp.max_iterations = 30;
  const auto d = decompose_takes(*p, dp);
  BlendParams bp;
  bp.alpha = 0.5;
  test::BlendRun scratch;
  MixResult locked, free;
  test::blend_into(*p, *d, bp, scratch, locked);
  bp.foot_lock = false;
  test::blend_into(*p, *d, bp, scratch, free);
  INFO(path_a << " / " << path_b << ": sliding A " << take_foot_sliding(*p, 0) << ", B " << take_foot_sliding(*p, 1)
              << ", raw " << locked.motion.foot_sliding_raw << ", cleaned " << locked.motion.foot_sliding_cleaned
              << ", inputs " << locked.foot_sliding_inputs);
  CHECK(free.motion.foot_sliding_cleaned == free.motion.foot_sliding_raw);
  CHECK(locked.motion.foot_sliding_raw == Approx(free.motion.foot_sliding_raw));
  // The measure is the one every take is measured with, on the output as it is.
  CHECK(locked.motion.foot_sliding_cleaned == Approx(planted_speed(locked.motion.world, p->feet).speed));
  CHECK(locked.foot_sliding_inputs == Approx(0.5 * (take_foot_sliding(*p, 0) + take_foot_sliding(*p, 1))));
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
    if (!leg) CHECK(locked.motion.world.middleCols(3 * c, 3) == free.motion.world.middleCols(3 * c, 3));
  }
}

}  // namespace

TEST_CASE("the pipeline locks planted feet of a real blend (assets, CMU)", "[foot_contact]") {
  check_pipeline_foot_lock(test::asset("motions/cmu142_walk_happy.bvh"), test::asset("motions/cmu142_walk_joy.bvh"));
}

TEST_CASE("the pipeline locks planted feet of real blends from ../shared/motions", "[foot_contact]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  check_pipeline_foot_lock(test::shared_motion("bandai_walk_normal.bvh"), test::shared_motion("bandai_walk_tired.bvh"));
  check_pipeline_foot_lock(test::shared_motion("cmu142_walk_joy.bvh"), test::shared_motion("bandai_walk_sad.bvh"));
}

TEST_CASE("foot contacts: foot strikes are landings, worked by hand", "[foot_contact]") {
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
