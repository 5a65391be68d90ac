#include "engine/align/alignment_feature.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "engine/base/error.h"

using namespace mostyle;

namespace {

constexpr double kFps = 30.0;
constexpr double kLeg = 1.0;     // leg length, file units
constexpr int kFrames = 90;
constexpr double kExact = 1e-12;

// Columns of the hand-built takes.
constexpr int kHips = 0, kLeftAnkle = 1, kRightAnkle = 2, kLeftWrist = 3, kRightWrist = 4, kHead = 5;
constexpr int kJoints = 6;

FeatureJoints all_joints() {
  FeatureJoints j;
  j.left_ankle = kLeftAnkle;
  j.right_ankle = kRightAnkle;
  j.left_wrist = kLeftWrist;
  j.right_wrist = kRightWrist;
  return j;
}

// A take of kJoints joints at fixed places, the given joints swinging along x with the given
// amplitudes (one cycle a second), the hips' ground moving along +Z at `speed` units a second.
CanonicalMotion take(double speed, const std::vector<std::pair<int, double>>& swinging, int joints = kJoints) {
  CanonicalMotion m;
  m.local = Eigen::MatrixXd::Zero(kFrames, 3 * joints);
  m.ground = Eigen::MatrixXd::Zero(kFrames, 2);
  m.heading = Eigen::VectorXd::Zero(kFrames);
  for (int t = 0; t < kFrames; ++t) {
    for (int j = 0; j < joints; ++j) m.local(t, 3 * j + 1) = 0.1 * j;
    for (const auto& [joint, amplitude] : swinging)
      m.local(t, 3 * joint) = amplitude * std::sin(2.0 * M_PI * t / kFps);
    m.ground(t, 1) = speed * t / kFps;
  }
  return m;
}

}  // namespace

TEST_CASE("alignment feature: travel speed in leg lengths per second", "[alignment_feature]") {
  CHECK(travel_speed(take(1.5, {}), kLeg, kFps) == Approx(1.5));
  CHECK(travel_speed(take(1.5, {}), 2.0 * kLeg, kFps) == Approx(0.75));
  CHECK(travel_speed(take(0.0, {{kHips, 1.0}}), kLeg, kFps) == 0.0);
}

TEST_CASE("alignment feature: auto picks the left foot when both takes travel, else the body",
          "[alignment_feature]") {
  const std::vector<std::pair<int, double>> swing = {{kLeftWrist, 10.0}, {kLeftAnkle, 2.0}};
  const CanonicalMotion walking = take(1.0, swing), walking_too = take(0.8, swing), standing = take(0.0, swing);
  SECTION("both travel: the left foot, as the paper does") {
    const AlignmentFeature f = alignment_feature(walking, walking_too, all_joints(), AlignOn::kAuto, kLeg, kFps);
    CHECK(f.locomotion);
    CHECK(f.on == AlignOn::kLeftFoot);
    CHECK(f.columns == std::vector<int>{kLeftAnkle});
    CHECK(f.weights == std::vector<double>{1.0});
    REQUIRE(f.a.rows() == kFrames);
    REQUIRE(f.a.cols() == 3);
    CHECK(f.a == walking.local.middleCols(3 * kLeftAnkle, 3));
    CHECK(f.b == walking_too.local.middleCols(3 * kLeftAnkle, 3));
  }
  for (const auto& [a, b, name] : {std::make_tuple(&walking, &standing, "A walks, B stands"),
                                   std::make_tuple(&standing, &walking, "A stands, B walks"),
                                   std::make_tuple(&standing, &standing, "both stand")}) {
    INFO(name);
    const AlignmentFeature f = alignment_feature(*a, *b, all_joints(), AlignOn::kAuto, kLeg, kFps);
    CHECK_FALSE(f.locomotion);
    CHECK(f.on == AlignOn::kBody);
    REQUIRE(!f.columns.empty());
    CHECK(f.columns.front() == kLeftWrist);  // the joint that moves
  }
  // Slow, but above the threshold, still counts.
  const CanonicalMotion slow = take(1.01 * kLocomotionLegsPerSecond * kLeg, swing);
  CHECK(alignment_feature(slow, slow, all_joints(), AlignOn::kAuto, kLeg, kFps).on == AlignOn::kLeftFoot);
  const CanonicalMotion slower = take(0.99 * kLocomotionLegsPerSecond * kLeg, swing);
  CHECK(alignment_feature(slower, slower, all_joints(), AlignOn::kAuto, kLeg, kFps).on == AlignOn::kBody);
}

TEST_CASE("alignment feature: body keeps the most moving joints, the strongest at weight 1",
          "[alignment_feature]") {
  SECTION("joints moving less than the minimum weight are left out") {
    // RMS of amplitude x sin is amplitude / sqrt(2): weights are amplitude ratios.
    const std::vector<std::pair<int, double>> swing = {{kLeftWrist, 10.0}, {kRightWrist, 6.0}, {kHead, 1.0}};
    const CanonicalMotion a = take(0.0, swing), b = take(0.0, swing);
    const AlignmentFeature f = alignment_feature(a, b, all_joints(), AlignOn::kBody, kLeg, kFps);
    CHECK(f.on == AlignOn::kBody);
    CHECK(f.columns == std::vector<int>{kLeftWrist, kRightWrist});
    REQUIRE(f.weights.size() == 2);
    CHECK(f.weights[0] == Approx(1.0).margin(kExact));
    CHECK(f.weights[1] == Approx(0.6).epsilon(1e-9));
    // The feature is the weighted canonical positions of those joints.
    REQUIRE(f.a.cols() == 6);
    const Eigen::MatrixXd left = f.weights[0] * a.local.middleCols(3 * kLeftWrist, 3);
    const Eigen::MatrixXd right = f.weights[1] * b.local.middleCols(3 * kRightWrist, 3);
    CHECK((f.a.middleCols(0, 3) - left).cwiseAbs().maxCoeff() < kExact);
    CHECK((f.b.middleCols(3, 3) - right).cwiseAbs().maxCoeff() < kExact);
  }
  SECTION("the hips never count, and moving most (a squat) they do not set the scale") {
    // In the canonical frame the hips move only up and down; in a squat more than any other joint.
    const std::vector<std::pair<int, double>> swing = {{kLeftWrist, 10.0}, {kRightWrist, 6.0}, {kHead, 1.0}};
    CanonicalMotion a = take(0.0, swing), b = take(0.0, swing);
    for (int t = 0; t < kFrames; ++t) {
      a.local(t, 3 * kHips + 1) = b.local(t, 3 * kHips + 1) = 20.0 * std::sin(2.0 * M_PI * t / kFps);
    }
    const AlignmentFeature f = alignment_feature(a, b, all_joints(), AlignOn::kBody, kLeg, kFps);
    CHECK(f.columns == std::vector<int>{kLeftWrist, kRightWrist});
    REQUIRE(!f.weights.empty());
    CHECK(f.weights[0] == Approx(1.0).margin(kExact));
  }
  SECTION("at most kBodyMaxJoints, weights in [kBodyMinWeight, 1], strongest first") {
    constexpr int kMany = 10;
    std::vector<std::pair<int, double>> swing;
    for (int j = 1; j < kMany; ++j) swing.emplace_back(j, 5.0 + 0.3 * j);  // all above the minimum
    const CanonicalMotion a = take(0.0, swing, kMany), b = take(0.0, swing, kMany);
    const AlignmentFeature f = alignment_feature(a, b, all_joints(), AlignOn::kBody, kLeg, kFps);
    REQUIRE(static_cast<int>(f.columns.size()) == kBodyMaxJoints);
    CHECK(f.columns.front() == kMany - 1);
    double strongest = 0;
    for (size_t k = 0; k < f.weights.size(); ++k) {
      INFO("column " << f.columns[k] << ", weight " << f.weights[k]);
      CHECK(f.weights[k] <= 1.0 + kExact);
      CHECK(f.weights[k] >= kBodyMinWeight);
      CHECK(f.columns[k] != kHips);
      if (k > 0) CHECK(f.weights[k] <= f.weights[k - 1]);
      strongest = std::max(strongest, f.weights[k]);
    }
    CHECK(strongest == Approx(1.0).margin(kExact));
    CHECK(f.a.cols() == 3 * kBodyMaxJoints);
  }
  SECTION("nothing moves: the left foot") {
    const CanonicalMotion still = take(0.0, {});
    const AlignmentFeature f = alignment_feature(still, still, all_joints(), AlignOn::kBody, kLeg, kFps);
    CHECK(f.columns == std::vector<int>{kLeftAnkle});
    FeatureJoints none;
    CHECK_THROWS_AS(alignment_feature(still, still, none, AlignOn::kBody, kLeg, kFps), InputError);
  }
}

TEST_CASE("alignment feature: feet and hands use both joints", "[alignment_feature]") {
  const CanonicalMotion a = take(1.0, {{kLeftWrist, 3.0}}), b = take(1.0, {{kRightWrist, 2.0}});
  const AlignmentFeature feet = alignment_feature(a, b, all_joints(), AlignOn::kFeet, kLeg, kFps);
  CHECK(feet.on == AlignOn::kFeet);
  CHECK(feet.columns == std::vector<int>{kLeftAnkle, kRightAnkle});
  CHECK(feet.a.cols() == 6);
  const AlignmentFeature hands = alignment_feature(a, b, all_joints(), AlignOn::kHands, kLeg, kFps);
  CHECK(hands.on == AlignOn::kHands);
  CHECK(hands.columns == std::vector<int>{kLeftWrist, kRightWrist});
  CHECK(hands.weights == std::vector<double>{1.0, 1.0});
  CHECK(hands.b.middleCols(3, 3) == b.local.middleCols(3 * kRightWrist, 3));
}

TEST_CASE("alignment feature: missing joints throw InputError", "[alignment_feature]") {
  const CanonicalMotion a = take(1.0, {{kLeftWrist, 3.0}});
  FeatureJoints no_hands = all_joints();
  no_hands.right_wrist = -1;
  CHECK_THROWS_AS(alignment_feature(a, a, no_hands, AlignOn::kHands, kLeg, kFps), InputError);
  CHECK_THROWS_WITH(alignment_feature(a, a, no_hands, AlignOn::kHands, kLeg, kFps), Catch::Contains("hands"));
  CHECK_NOTHROW(alignment_feature(a, a, no_hands, AlignOn::kFeet, kLeg, kFps));
  FeatureJoints no_feet = all_joints();
  no_feet.left_ankle = -1;
  CHECK_THROWS_WITH(alignment_feature(a, a, no_feet, AlignOn::kLeftFoot, kLeg, kFps), Catch::Contains("left foot"));
  CHECK_THROWS_AS(alignment_feature(a, a, no_feet, AlignOn::kFeet, kLeg, kFps), InputError);
  CHECK_THROWS_AS(alignment_feature(a, a, no_feet, AlignOn::kAuto, kLeg, kFps), InputError);  // both travel
}

TEST_CASE("alignment feature: names round trip, junk is refused", "[alignment_feature]") {
  for (AlignOn on : {AlignOn::kAuto, AlignOn::kLeftFoot, AlignOn::kFeet, AlignOn::kHands, AlignOn::kBody}) {
    INFO(align_on_name(on));
    CHECK(parse_align_on(align_on_name(on)) == on);
  }
  CHECK(std::string(align_on_name(AlignOn::kLeftFoot)) == "left-foot");
  for (const char* junk : {"", "Left-Foot", "left_foot", "hand", "body ", "everything"}) {
    INFO("'" << junk << "'");
    CHECK_THROWS_AS(parse_align_on(junk), InputError);
    CHECK_THROWS_WITH(parse_align_on(junk), Catch::Contains("auto, left-foot, feet, hands or body"));
  }
}
