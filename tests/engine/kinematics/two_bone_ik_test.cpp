#include "engine/kinematics/two_bone_ik.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

using namespace mostyle;

namespace {

constexpr double kExact = 1e-9;  // file units (cm here): IK holds to rounding
// A target out of reach stops kChainMargin of the chain (7e-9 here) short of where the bones
// reach; the middle joint then lies about the square root of that (times the bones) off the line.
constexpr double kClampedEnd = 1e-7;
constexpr double kClampedMid = 1e-3;

// A chain with bones of 3 and 4 (start at the origin, bent towards +Y), aimed at `target` with
// `pole`.
TwoBoneIkJob three_four_chain(const Eigen::Vector3d& target, const Eigen::Vector3d& pole) {
  TwoBoneIkJob job;
  job.start = Eigen::Vector3d::Zero();
  job.mid = Eigen::Vector3d(0, 3, 0);
  job.end = Eigen::Vector3d(4, 3, 0);
  job.target = target;
  job.pole = pole;
  job.bend_fallback = Eigen::Vector3d::UnitY();
  return job;
}

}  // namespace

TEST_CASE("two-bone IK, worked by hand: a 3-4-5 triangle reaches its target exactly", "[two_bone_ik]") {
  // Bones 3 and 4, the target 5 away on +X: the middle joint 1.8 along the line (9 - 16 + 25 over
  // 10) and 2.4 off it (the square root of 9 - 1.8^2), on the pole's side.
  const TwoBoneIkResult r = three_four_chain(Eigen::Vector3d(5, 0, 0), Eigen::Vector3d(0, 1, 0)).Run();
  CHECK(r.reached);
  CHECK((r.end - Eigen::Vector3d(5, 0, 0)).norm() < kExact);
  CHECK((r.mid - Eigen::Vector3d(1.8, 2.4, 0)).norm() < kExact);
}

TEST_CASE("two-bone IK, worked by hand: the pole's side is kept, its part along the line ignored",
          "[two_bone_ik]") {
  const Eigen::Vector3d target(5, 0, 0);
  CHECK((three_four_chain(target, Eigen::Vector3d(0, 0, 1)).Run().mid - Eigen::Vector3d(1.8, 0, 2.4)).norm() < kExact);
  CHECK((three_four_chain(target, Eigen::Vector3d(0, 0, -1)).Run().mid - Eigen::Vector3d(1.8, 0, -2.4)).norm() <
        kExact);
  CHECK((three_four_chain(target, Eigen::Vector3d(7, -2, 0)).Run().mid - Eigen::Vector3d(1.8, -2.4, 0)).norm() <
        kExact);
}

TEST_CASE("two-bone IK, worked by hand: a target out of reach is clamped to it", "[two_bone_ik]") {
  SECTION("too far: a straight chain towards it") {
    const TwoBoneIkResult r = three_four_chain(Eigen::Vector3d(10, 0, 0), Eigen::Vector3d(0, 1, 0)).Run();
    CHECK_FALSE(r.reached);
    CHECK((r.end - Eigen::Vector3d(7, 0, 0)).norm() < kClampedEnd);
    CHECK((r.mid - Eigen::Vector3d(3, 0, 0)).norm() < kClampedMid);
    CHECK(r.mid.y() > 0.0);  // still bent, by a hair, on the pole's side
  }
  SECTION("too near: folded, the end 4 - 3 = 1 from the start") {
    const TwoBoneIkResult r = three_four_chain(Eigen::Vector3d(0.5, 0, 0), Eigen::Vector3d(0, 1, 0)).Run();
    CHECK_FALSE(r.reached);
    CHECK((r.end - Eigen::Vector3d(1, 0, 0)).norm() < kClampedEnd);
    CHECK((r.mid - Eigen::Vector3d(-3, 0, 0)).norm() < kClampedMid);
  }
}

TEST_CASE("two-bone IK, worked by hand: a straight chain bends along the fallback", "[two_bone_ik]") {
  // Bones 1 and 1 along -Y, the target sqrt(2) below the start: a right angle at the middle
  // joint, which goes half of sqrt(2) down and half of sqrt(2) towards the fallback (+X).
  TwoBoneIkJob job;
  job.mid = Eigen::Vector3d(0, -1, 0);
  job.end = Eigen::Vector3d(0, -2, 0);
  job.target = Eigen::Vector3d(0, -std::sqrt(2.0), 0);
  job.pole = job.mid - job.start;  // the chain's own bend: none, it is straight
  job.bend_fallback = Eigen::Vector3d(1, 0, 0);
  const TwoBoneIkResult r = job.Run();
  CHECK(r.reached);
  CHECK((r.end - job.target).norm() < kExact);
  CHECK((r.mid - Eigen::Vector3d(std::sqrt(0.5), -std::sqrt(0.5), 0)).norm() < kExact);
}

TEST_CASE("two-bone IK reaches what it can, keeps lengths and the knee's bend", "[two_bone_ik]") {
  TwoBoneIkJob job;
  job.start = Eigen::Vector3d(0, 80, 0);
  job.mid = Eigen::Vector3d(5, 42, 3);
  job.end = Eigen::Vector3d(0, 5, 0);
  job.pole = job.mid - job.start;
  job.bend_fallback = Eigen::Vector3d(1, 0, 0);
  const double thigh = (job.mid - job.start).norm(), shin = (job.end - job.mid).norm();
  SECTION("a reachable target") {
    job.target = Eigen::Vector3d(20, 10, -5);
    const TwoBoneIkResult r = job.Run();
    CHECK(r.reached);
    CHECK((r.end - job.target).norm() < kExact);
    CHECK((r.mid - job.start).norm() == Approx(thigh).epsilon(1e-12));
    CHECK((r.end - r.mid).norm() == Approx(shin).epsilon(1e-12));
    // The knee still bends the way it did (toward +X, +Z here).
    const Eigen::Vector3d n = (job.target - job.start).normalized();
    const Eigen::Vector3d old_bend = (job.mid - job.start) - n * n.dot(job.mid - job.start);
    const Eigen::Vector3d new_bend = (r.mid - job.start) - n * n.dot(r.mid - job.start);
    CHECK(old_bend.dot(new_bend) > 0);
    CHECK(std::abs(old_bend.normalized().cross(new_bend.normalized()).norm()) < 1e-9);
  }
  SECTION("the ankle where it is: nothing moves") {
    job.target = job.end;
    const TwoBoneIkResult r = job.Run();
    CHECK((r.end - job.end).norm() < kExact);
    CHECK((r.mid - job.mid).norm() < kExact);
  }
  SECTION("the target on the hip: no direction, the chain as it is") {
    job.target = job.start;
    const TwoBoneIkResult r = job.Run();
    CHECK_FALSE(r.reached);
    CHECK(r.end == job.end);
    CHECK(r.mid == job.mid);
  }
}

TEST_CASE("two-bone IK: a job with a value that is not finite does not validate and moves nothing",
          "[two_bone_ik][errors]") {
  const TwoBoneIkJob good = three_four_chain(Eigen::Vector3d(5, 0, 0), Eigen::Vector3d(0, 1, 0));
  CHECK(good.Validate());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (Eigen::Vector3d TwoBoneIkJob::*input : {&TwoBoneIkJob::start, &TwoBoneIkJob::mid, &TwoBoneIkJob::end,
                                               &TwoBoneIkJob::target, &TwoBoneIkJob::pole,
                                               &TwoBoneIkJob::bend_fallback}) {
    TwoBoneIkJob bad = good;
    (bad.*input).y() = nan;
    CHECK_FALSE(bad.Validate());
    const TwoBoneIkResult r = bad.Run();
    CHECK_FALSE(r.reached);
    CHECK(r.end.x() == good.end.x());
    CHECK(r.mid.x() == good.mid.x());
  }
}
