#include "engine/kinematics/two_bone_ik.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

using namespace mostyle;

namespace {

constexpr double kExact = 1e-9;   // file units (cm here): IK holds to rounding

}  // namespace

TEST_CASE("two-bone IK reaches what it can, keeps lengths and the knee's bend", "[two_bone_ik]") {
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
