#include "engine/post/swing_clearance.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "engine/base/error.h"
#include "engine/measure/planted_feet.h"

using namespace mostyle;

namespace {

constexpr double kFps = 30.0;
constexpr double kHeight = 100.0;  // body height: the planted band is 3 units
constexpr int kFrames = 30;
constexpr int kAirFirst = 14, kAirLast = 25;  // the frames the takes hold the left foot in the air
constexpr double kTolerance = 1e-9;

// Columns: left hip, knee, ankle, toe, then the right leg's.
FootRig rig() {
  FootRig r;
  r.legs[0] = {0, 1, 2, 3};
  r.legs[1] = {4, 5, 6, 7};
  r.leg_length = 80.0;
  r.body_height = kHeight;
  r.fps = kFps;
  return r;
}

Eigen::Vector3d at(const Eigen::MatrixXd& w, int f, int c) { return w.block<1, 3>(f, 3 * c).transpose(); }

void put(Eigen::MatrixXd& w, int f, int c, const Eigen::Vector3d& v) { w.block<1, 3>(f, 3 * c) = v.transpose(); }

// Hips 20 apart along x, the body facing +z. The left foot planted (ankle 1 above the floor, toe
// on it) for frames 0-9, then moving forwards along z half a unit above that, inside the band,
// the whole time; its knee bent slightly forwards. The right foot planted and still.
Eigen::MatrixXd skimming() {
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(kFrames, 24);
  for (int f = 0; f < kFrames; ++f) {
    const double z = f < 10 ? 0.0 : 0.5 * (f - 9);
    const double lift = f < 10 ? 0.0 : 0.5;
    for (int side = 0; side < 2; ++side) {
      const double x = side == 0 ? 10.0 : -10.0;
      const double dz = side == 0 ? z : 0.0, dy = side == 0 ? lift : 0.0;
      put(w, f, 4 * side, {x, 80.0, 0.0});
      put(w, f, 4 * side + 1, {x, 40.0 + 0.5 * dy, 0.5 * dz + 2.0});
      put(w, f, 4 * side + 2, {x, 1.0 + dy, dz});
      put(w, f, 4 * side + 3, {x, 0.0 + dy, dz + 8.0});
    }
  }
  return w;
}

Eigen::MatrixXd left_in_air() {
  Eigen::MatrixXd air = Eigen::MatrixXd::Zero(kFrames, kFootJoints);
  air.block(kAirFirst, 0, kAirLast - kAirFirst + 1, 2).setOnes();
  return air;
}

}  // namespace

TEST_CASE("swing clearance lifts a foot the takes hold in the air out of the planted band", "[swing_clearance]") {
  const Eigen::MatrixXd before = skimming();
  Eigen::MatrixXd w = before;
  SwingClearanceScratch scratch;
  const double largest = lift_swinging_feet(w, rig(), left_in_air(), scratch);
  const double clear = kSwingClearanceBands * kPlantedHeightFraction * kHeight;  // 3.75
  // Both joints were 0.5 above their floors (1 and 0): lifted by 3.25.
  CHECK(largest == Approx(clear - 0.5).margin(kTolerance));
  for (int f = kAirFirst; f <= kAirLast; ++f) {
    CHECK(at(w, f, 2).y() - 1.0 >= clear - kTolerance);
    CHECK(at(w, f, 3).y() >= clear - kTolerance);
    // The leg keeps its bones, the hip stays, the toe moves with the ankle, the knee bends forwards.
    CHECK((at(w, f, 1) - at(w, f, 0)).norm() == Approx((at(before, f, 1) - at(before, f, 0)).norm()).epsilon(1e-12));
    CHECK((at(w, f, 2) - at(w, f, 1)).norm() == Approx((at(before, f, 2) - at(before, f, 1)).norm()).epsilon(1e-12));
    CHECK((at(w, f, 0) - at(before, f, 0)).norm() == 0.0);
    CHECK(((at(w, f, 3) - at(w, f, 2)) - (at(before, f, 3) - at(before, f, 2))).norm() < kTolerance);
    CHECK(at(w, f, 1).z() > at(before, f, 1).z());
  }
  // Eased in over kSwingEaseSeconds (3 frames) before the swing: frames before that are as they were.
  const int ramp = 3;
  CHECK(w.topRows(kAirFirst - ramp) == before.topRows(kAirFirst - ramp));
  for (int f = kAirFirst - ramp; f < kAirFirst; ++f) {
    const double lifted = at(w, f, 2).y() - at(before, f, 2).y();
    CHECK(lifted > 0.0);
    CHECK(lifted < clear - 0.5);
  }
  // The right leg is not touched.
  CHECK(w.middleCols(12, 12) == before.middleCols(12, 12));
}

TEST_CASE("swing clearance leaves feet alone where the takes plant them or they are clear", "[swing_clearance]") {
  const Eigen::MatrixXd before = skimming();
  SwingClearanceScratch scratch;
  Eigen::MatrixXd w = before;
  CHECK(lift_swinging_feet(w, rig(), Eigen::MatrixXd::Zero(kFrames, kFootJoints), scratch) == 0.0);
  CHECK(w == before);
  // The same foot lifted 5 above the band by the motion itself: nothing to lift.
  Eigen::MatrixXd high = before;
  for (int f = 10; f < kFrames; ++f)
    for (int c = 1; c <= 3; ++c) high(f, 3 * c + 1) += c == 1 ? 0.0 : 8.0;
  w = high;
  CHECK(lift_swinging_feet(w, rig(), left_in_air(), scratch) == 0.0);
  CHECK(w == high);
}

TEST_CASE("swing clearance refuses a mask of the wrong shape", "[swing_clearance]") {
  Eigen::MatrixXd w = skimming();
  SwingClearanceScratch scratch;
  CHECK_THROWS_AS(lift_swinging_feet(w, rig(), Eigen::MatrixXd::Zero(kFrames - 1, kFootJoints), scratch), InputError);
  CHECK_THROWS_AS(lift_swinging_feet(w, rig(), Eigen::MatrixXd::Zero(kFrames, 2), scratch), InputError);
}

TEST_CASE("swing clearance lifts a swing sunk below the floor clear of the planted frames' floor",
          "[swing_clearance]") {
  // The skimming foot sunk 2 below its planted height while the takes hold it in the air: those
  // frames are the joint's lowest, its floor, until they are lifted; the passes lift them clear of
  // the floor the planted frames give.
  Eigen::MatrixXd before = skimming();
  for (int f = kAirFirst; f <= kAirLast; ++f)
    for (int c = 1; c <= 3; ++c) before(f, 3 * c + 1) -= c == 1 ? 1.0 : 2.5;
  Eigen::MatrixXd w = before;
  SwingClearanceScratch scratch;
  lift_swinging_feet(w, rig(), left_in_air(), scratch);
  const double clear = kSwingClearanceBands * kPlantedHeightFraction * kHeight;
  for (int f = kAirFirst; f <= kAirLast; ++f) {
    CHECK(at(w, f, 2).y() - 1.0 >= clear - kTolerance);
    CHECK(at(w, f, 3).y() >= clear - kTolerance);
  }
}

namespace {

// Standing: both feet flat (ankle 1 above the floor, toe on it, 8 ahead), the knees bent
// forwards. On frames first..last the left heel is raised by `raise` about a toe that stays
// where it is (the foot pitched, its length kept): what a style's lifting heel put on a content
// that stands flat gives.
Eigen::MatrixXd heel_raised(int first, int last, double raise) {
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(kFrames, 24);
  const double foot = std::sqrt(65.0);
  for (int f = 0; f < kFrames; ++f)
    for (int side = 0; side < 2; ++side) {
      const double x = side == 0 ? 10.0 : -10.0;
      const double up = side == 0 && f >= first && f <= last ? raise : 0.0;
      const double ankle_z = 8.0 - std::sqrt(foot * foot - (1.0 + up) * (1.0 + up));
      put(w, f, 4 * side, {x, 80.0, 0.0});
      put(w, f, 4 * side + 1, {x, 40.0 + 0.5 * up, 12.0 + 0.5 * ankle_z});
      put(w, f, 4 * side + 2, {x, 1.0 + up, ankle_z});
      put(w, f, 4 * side + 3, {x, 0.0, 8.0});
    }
  return w;
}

// The takes' feet: every joint flat on its floor (0 bands above it), held on frames first..last.
void takes_flat(int first, int last, Eigen::MatrixXd& heights, Eigen::MatrixXd& held) {
  heights = Eigen::MatrixXd::Zero(kFrames, kFootJoints);
  held = Eigen::MatrixXd::Zero(kFrames, kFootJoints);
  held.middleRows(first, last - first + 1).setOnes();
}

double bone(const Eigen::MatrixXd& w, int f, int a, int b) { return (at(w, f, a) - at(w, f, b)).norm(); }

}  // namespace

TEST_CASE("settling planted feet puts a raised heel down where the takes hold the foot flat", "[swing_clearance]") {
  const Eigen::MatrixXd before = heel_raised(10, 19, 2.0);
  Eigen::MatrixXd heights, held;
  takes_flat(0, kFrames - 1, heights, held);
  Eigen::MatrixXd w = before;
  SwingClearanceScratch scratch;
  CHECK(settle_held_feet(w, rig(), heights, held, scratch) == Approx(2.0).margin(kTolerance));
  for (int f = 10; f <= 19; ++f) {
    // The heel down on its floor (1), the toe on its (0), the foot's length and way kept: flat again.
    CHECK(at(w, f, 2).y() == Approx(1.0).margin(kTolerance));
    CHECK(at(w, f, 3).y() == Approx(0.0).margin(kTolerance));
    CHECK(bone(w, f, 3, 2) == Approx(std::sqrt(65.0)).epsilon(1e-12));
    CHECK((at(w, f, 3) - at(w, f, 2)).x() == Approx(0.0).margin(kTolerance));
    CHECK((at(w, f, 3) - at(w, f, 2)).z() == Approx(8.0).margin(kTolerance));
    // Two-bone IK: the hip stays, thigh and shin keep their lengths.
    CHECK(at(w, f, 0) == at(before, f, 0));
    CHECK(bone(w, f, 1, 0) == Approx(bone(before, f, 1, 0)).epsilon(1e-12));
    CHECK(bone(w, f, 2, 1) == Approx(bone(before, f, 2, 1)).epsilon(1e-12));
  }
  // Frames already as the takes hold them, and the right leg, are left exactly as they were.
  CHECK(w.topRows(10) == before.topRows(10));
  CHECK(w.bottomRows(kFrames - 20) == before.bottomRows(kFrames - 20));
  CHECK(w.middleCols(12, 12) == before.middleCols(12, 12));
}

TEST_CASE("settling planted feet eases in and out of the frames the takes hold", "[swing_clearance]") {
  // The heel raised on frames 5-24, the takes holding the foot flat on frames 10-19 only (in the
  // air around them, say): the ease runs over kSwingEaseSeconds (3 frames) either side.
  const Eigen::MatrixXd before = heel_raised(5, 24, 2.0);
  Eigen::MatrixXd heights, held;
  takes_flat(10, 19, heights, held);
  Eigen::MatrixXd w = before;
  SwingClearanceScratch scratch;
  settle_held_feet(w, rig(), heights, held, scratch);
  const int ramp = 3;
  for (int f = 10; f <= 19; ++f) CHECK(at(w, f, 2).y() == Approx(1.0).margin(kTolerance));
  double last_down = 0.0;
  for (int f = 10 - ramp; f < 10; ++f) {
    const double down = at(before, f, 2).y() - at(w, f, 2).y();
    CHECK(down > last_down);
    CHECK(down < 2.0);
    last_down = down;
  }
  CHECK(w.topRows(10 - ramp) == before.topRows(10 - ramp));
  CHECK(w.bottomRows(kFrames - 20 - ramp) == before.bottomRows(kFrames - 20 - ramp));
}

TEST_CASE("settling planted feet leaves a foot the output swings in the air", "[swing_clearance]") {
  // The heel raised 8 on frames 10-19 (beyond the 3-unit band, and the toe with it): the output
  // swings that foot; bringing it down would make a swing at its speed read as a sliding plant.
  Eigen::MatrixXd before = heel_raised(10, 19, 0.0);
  for (int f = 10; f <= 19; ++f)
    for (int c = 1; c <= 3; ++c) before(f, 3 * c + 1) += c == 1 ? 4.0 : 8.0;
  Eigen::MatrixXd heights, held;
  takes_flat(0, kFrames - 1, heights, held);
  Eigen::MatrixXd w = before;
  SwingClearanceScratch scratch;
  settle_held_feet(w, rig(), heights, held, scratch);
  for (int f = 10; f <= 19; ++f) {
    CHECK(at(w, f, 2) == at(before, f, 2));
    CHECK(at(w, f, 3) == at(before, f, 3));
  }
  CHECK_THROWS_AS(settle_held_feet(w, rig(), heights.topRows(kFrames - 1), held, scratch), InputError);
  CHECK_THROWS_AS(settle_held_feet(w, rig(), heights, held.leftCols(2), scratch), InputError);
}
