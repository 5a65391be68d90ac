#include "engine/measure/planted_feet.h"

#include <catch2/catch.hpp>
#include <vector>

#include "engine/base/error.h"
#include "engine/prepare/major_skeleton.h"

using namespace mostyle;

namespace {

constexpr double kFps = 30.0;
constexpr double kHeight = 100.0;  // body height: planted within 3 units of a joint's floor
constexpr int kFrames = 30;

// Columns: left hip, knee, ankle, toe, then the right leg's; toes only when `toes`.
FootRig rig(bool toes) {
  FootRig r;
  r.legs[0] = {0, 1, 2, toes ? 3 : -1};
  r.legs[1] = {4, 5, 6, toes ? 7 : -1};
  r.leg_length = 80.0;
  r.body_height = kHeight;
  r.fps = kFps;
  return r;
}

void put(Eigen::MatrixXd& w, int f, int c, double x, double y, double z) {
  w(f, 3 * c) = x;
  w(f, 3 * c + 1) = y;
  w(f, 3 * c + 2) = z;
}

// The left foot planted and still for frames 0-9, on the floor and sliding 1 unit a frame along
// x from frame 10 to 19 (30 units/s), lifted 10 units and moving fast for frames 20-29; the right
// foot planted and still throughout. Toes 12 units ahead of their ankles, 2 lower.
Eigen::MatrixXd slide() {
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(kFrames, 24);
  for (int f = 0; f < kFrames; ++f) {
    const double x = f < 10 ? 0.0 : f < 20 ? f - 9.0 : 10.0 + 5.0 * (f - 19);
    const double y = f < 20 ? 8.0 : 18.0;
    put(w, f, 0, 0, 80, 10);
    put(w, f, 1, 0, 44, 10);
    put(w, f, 2, x, y, 10);
    put(w, f, 3, x + 12, y - 2, 10);
    put(w, f, 4, 0, 80, -10);
    put(w, f, 5, 0, 44, -10);
    put(w, f, 6, 0, 8, -10);
    put(w, f, 7, 12, 6, -10);
  }
  return w;
}

}  // namespace

TEST_CASE("planted feet: a foot planted, then sliding at a known speed, worked by hand", "[planted_feet]") {
  const Eigen::MatrixXd w = slide();
  SECTION("ankles only") {
    const FootRig r = rig(false);
    Eigen::MatrixXd planted;
    std::vector<double> heights;
    std::array<double, kFootJoints> floors;
    planted_frames(w, r, planted, heights, &floors);
    // Left ankle: its floor is the 5th percentile of 20 frames at 8 and 10 at 18 (8); planted on
    // frames 0-19. The right ankle: always at its floor.
    CHECK(floors[0] == 8.0);
    CHECK(planted.col(0).head(20).minCoeff() == 1.0);
    CHECK(planted.col(0).tail(10).maxCoeff() == 0.0);
    CHECK(planted.col(2).minCoeff() == 1.0);
    CHECK(planted.col(1).maxCoeff() == 0.0);  // no toes in this rig
    CHECK(planted.col(3).maxCoeff() == 0.0);
    // Left: 19 planted steps, 10 of them (9 -> 10 .. 18 -> 19) moving 1 unit; right: 29 still.
    const PlantedSpeed s = planted_speed(w, planted, r);
    CHECK(s.steps == 19 + 29);
    CHECK(s.speed == Approx(10.0 * 30.0 / 48.0));
    CHECK(s.of_height() == Approx(10.0 * 30.0 / 48.0 / kHeight));
    CHECK(planted_speed(w, r).speed == Approx(s.speed));
  }
  SECTION("ankles and toes pooled") {
    // The toes move with their ankles: twice the steps, twice the moving ones, the same speed.
    const PlantedSpeed s = planted_speed(w, rig(true));
    CHECK(s.steps == 2 * (19 + 29));
    CHECK(s.speed == Approx(10.0 * 30.0 / 48.0));
  }
  SECTION("a joint just above the band is not planted; the band is the body's height") {
    Eigen::MatrixXd lifted = w;
    for (int f = 10; f < 20; ++f) lifted(f, 3 * 2 + 1) = 8.0 + 3.01;  // left ankle 3.01 above its floor
    Eigen::MatrixXd planted;
    std::vector<double> heights;
    planted_frames(lifted, rig(false), planted, heights);
    CHECK(planted.col(0).head(10).minCoeff() == 1.0);
    CHECK(planted.col(0).segment(10, 10).maxCoeff() == 0.0);
    CHECK(planted_speed(lifted, rig(false)).speed == 0.0);  // the slide is no longer planted
    FootRig taller = rig(false);
    taller.body_height = 101.0;  // 3% of it is 3.03: planted again
    CHECK(planted_speed(lifted, taller).speed == Approx(10.0 * 30.0 / 48.0));
  }
}

TEST_CASE("planted feet: nothing planted is no speed; bad input is refused", "[planted_feet]") {
  const FootRig r = rig(true);
  CHECK(planted_speed(Eigen::MatrixXd::Zero(0, 24), r).speed == 0.0);
  CHECK(planted_speed(Eigen::MatrixXd::Zero(1, 24), r).steps == 0);
  Eigen::MatrixXd planted;
  std::vector<double> heights;
  CHECK_THROWS_AS(planted_frames(Eigen::MatrixXd::Zero(5, 12), r, planted, heights), InputError);
  CHECK_THROWS_AS(planted_speed(Eigen::MatrixXd::Zero(5, 24), Eigen::MatrixXd::Zero(4, kFootJoints), r), InputError);
  FootRig no_height = r;
  no_height.body_height = 0.0;
  CHECK_THROWS_AS(planted_speed(Eigen::MatrixXd::Zero(5, 24), no_height), InputError);
}

TEST_CASE("planted feet: the body's height is the leg and the trunk stood upright", "[planted_feet]") {
  using J = MajorJoint;
  const std::vector<int> majors = {int(J::kHips),     int(J::kSpine),     int(J::kChest),     int(J::kHead),
                                   int(J::kLeftHip),  int(J::kLeftKnee),  int(J::kLeftAnkle), int(J::kRightHip),
                                   int(J::kRightKnee), int(J::kRightAnkle)};
  // Bone lengths into each joint from its parent: spine 10, chest 20, head 25; thighs 40 and 42,
  // shins 40 and 38 (legs 80 on average).
  const std::vector<double> lengths = {0, 10, 20, 25, 9, 40, 40, 9, 42, 38};
  CHECK(standing_height(majors, lengths) == Approx(80.0 + 55.0));
  // Without knees there is no leg: no height.
  CHECK(standing_height({int(J::kHips), int(J::kSpine)}, {0, 10}) == 0.0);
}
