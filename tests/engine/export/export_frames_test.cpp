#include "engine/export/export_frames.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "engine/base/error.h"

using namespace mostyle;

namespace {

// Interpolated values are sums of a few exact numbers: equal to rounding.
constexpr double kRounding = 1e-12;

// F frames of one joint: x = f(row), y = 10 + row, z = -row.
template <typename F>
Eigen::MatrixXd one_joint(int frames, F x_of_row) {
  Eigen::MatrixXd w(frames, 3);
  for (int r = 0; r < frames; ++r) w.row(r) << x_of_row(r), 10.0 + r, -double(r);
  return w;
}

Eigen::VectorXd rows_times(int frames, double scale) {
  Eigen::VectorXd at(frames);
  for (int r = 0; r < frames; ++r) at[r] = scale * r;
  return at;
}

}  // namespace

TEST_CASE("export frames: 30 to 60 fps doubles the frames minus one, interpolating between them") {
  // x = row squared, so a midpoint is not a row's value: 0, 1, 4, 9.
  const Eigen::MatrixXd world = one_joint(4, [](int r) { return double(r * r); });
  const Eigen::VectorXd at = rows_times(4, 4.0);  // A at 120 fps under a 30 fps blend
  const ExportFrames out = export_frames(world, at, 30.0, 60.0, 0.0, motion_length_s(4, 30.0));
  REQUIRE(out.frames() == 7);
  CHECK(out.fps == 60.0);
  REQUIRE(out.at.size() == 7);
  const double x[7] = {0.0, 0.5, 1.0, 2.5, 4.0, 6.5, 9.0};
  for (int k = 0; k < 7; ++k) {
    CHECK(out.world(k, 0) == Approx(x[k]).margin(kRounding));
    CHECK(out.world(k, 1) == Approx(10.0 + 0.5 * k).margin(kRounding));
    CHECK(out.world(k, 2) == Approx(-0.5 * k).margin(kRounding));
    CHECK(out.at[k] == Approx(2.0 * k).margin(kRounding));
  }
  // Frames that land on the blend's own frames are those frames, exactly.
  for (int k = 0; k < 7; k += 2) {
    CHECK(out.world.row(k) == world.row(k / 2));
    CHECK(out.at[k] == at[k / 2]);
  }
}

TEST_CASE("export frames: at the blend's own rate over all of it, the blend as it is") {
  const Eigen::MatrixXd world = one_joint(31, [](int r) { return std::sin(0.3 * r); });
  const Eigen::VectorXd at = rows_times(31, 4.0);
  const ExportFrames out = export_frames(world, at, 30.0, 30.0, 0.0, motion_length_s(31, 30.0));
  CHECK(out.world == world);
  CHECK(out.at == at);
}

TEST_CASE("export frames: a range cuts the frames from its first time to its last, both included") {
  const Eigen::MatrixXd world = one_joint(31, [](int r) { return double(r); });  // x = row, 1 s at 30 fps
  const Eigen::VectorXd at = rows_times(31, 1.0);
  SECTION("at the blend's rate: rows 15 to 24") {
    const ExportFrames out = export_frames(world, at, 30.0, 30.0, 0.5, 0.8);
    REQUIRE(out.frames() == 10);
    CHECK(out.world(0, 0) == 15.0);
    CHECK(out.world(9, 0) == 24.0);
    CHECK(out.at[9] == 24.0);
  }
  SECTION("at 60 fps: the same span in half frames") {
    const ExportFrames out = export_frames(world, at, 30.0, 60.0, 0.5, 0.8);
    REQUIRE(out.frames() == 19);
    CHECK(out.world(1, 0) == Approx(15.5).margin(kRounding));
    CHECK(out.world(18, 0) == Approx(24.0).margin(kRounding));
  }
  SECTION("one instant: one frame") {
    const ExportFrames out = export_frames(world, at, 30.0, 30.0, 10.0 / 30.0, 10.0 / 30.0);
    REQUIRE(out.frames() == 1);
    CHECK(out.world(0, 0) == 10.0);
  }
  SECTION("an end between two output frames: the frame before it is the last") {
    const ExportFrames out = export_frames(world, at, 30.0, 30.0, 0.0, 0.51);  // row 15.3
    REQUIRE(out.frames() == 16);
    CHECK(out.world(15, 0) == 15.0);
  }
  SECTION("ends within rounding of the motion's ends count as the ends") {
    const ExportFrames out = export_frames(world, at, 30.0, 30.0, -1e-12, 1.0 + 1e-12);
    REQUIRE(out.frames() == 31);
    CHECK(out.world(30, 0) == 30.0);
  }
}

TEST_CASE("export frames: 120 to 30 fps keeps every fourth frame") {
  const Eigen::MatrixXd world = one_joint(9, [](int r) { return double(r); });
  const Eigen::VectorXd at = rows_times(9, 1.0);
  const ExportFrames out = export_frames(world, at, 120.0, 30.0, 0.0, motion_length_s(9, 120.0));
  REQUIRE(out.frames() == 3);
  CHECK(out.world(0, 0) == 0.0);
  CHECK(out.world(1, 0) == 4.0);
  CHECK(out.world(2, 0) == 8.0);
  CHECK(out.at[2] == 8.0);
  // A quarter of an output frame more at the end is not a frame.
  const Eigen::MatrixXd longer = one_joint(10, [](int r) { return double(r); });
  CHECK(export_frames(longer, rows_times(10, 1.0), 120.0, 30.0, 0.0, motion_length_s(10, 120.0)).frames() == 3);
}

TEST_CASE("export frames: a loop resamples over its period, through the seam to its repeat") {
  // Walking +1 in x per frame, z still; the loop carries the first frame 4 on in x and 2 in z.
  Eigen::MatrixXd world = one_joint(4, [](int r) { return double(r); });
  world.col(2).setZero();
  const Eigen::VectorXd at = rows_times(4, 1.0);
  const Eigen::Vector2d travel(4.0, 2.0);
  SECTION("at 60 fps: twice the frames, the last half way to the repeat") {
    const ExportFrames out = export_loop_frames(world, at, 30.0, 60.0, travel);
    REQUIRE(out.frames() == 8);
    for (int k = 0; k < 8; ++k) CHECK(out.world(k, 0) == Approx(0.5 * k).margin(kRounding));
    CHECK(out.world(7, 1) == Approx(10.0 + 1.5).margin(kRounding));  // y: between row 3 (13) and row 0 (10)
    CHECK(out.world(7, 2) == Approx(1.0).margin(kRounding));         // z: half the travel
    CHECK(out.world(6, 2) == 0.0);
    CHECK(out.at[7] == Approx(3.5).margin(kRounding));  // A's frames go on past the last
  }
  SECTION("at the blend's rate: the loop as it is") {
    const ExportFrames out = export_loop_frames(world, at, 30.0, 30.0, travel);
    CHECK(out.world == world);
    CHECK(out.at == at);
  }
  SECTION("at 20 fps: the period in round(4 x 20 / 30) = 3 even steps") {
    const ExportFrames out = export_loop_frames(world, at, 30.0, 20.0, travel);
    REQUIRE(out.frames() == 3);
    CHECK(out.world(1, 0) == Approx(4.0 / 3.0).margin(kRounding));
    CHECK(out.world(2, 0) == Approx(8.0 / 3.0).margin(kRounding));
  }
}

TEST_CASE("export frames: a bad rate, range or motion is an InputError that says which") {
  const Eigen::MatrixXd world = one_joint(31, [](int r) { return double(r); });
  const Eigen::VectorXd at = rows_times(31, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double fps : {0.0, -30.0, 1000.5, nan, inf}) {
    CHECK_THROWS_AS(export_frames(world, at, 30.0, fps, 0.0, 1.0), InputError);
    CHECK_THROWS_WITH(export_frames(world, at, 30.0, fps, 0.0, 1.0), Catch::Contains("output frame rate"));
    CHECK_THROWS_WITH(export_frames(world, at, fps, 30.0, 0.0, 1.0), Catch::Contains("blend's frame rate"));
    CHECK_THROWS_AS(export_loop_frames(world, at, 30.0, fps, Eigen::Vector2d::Zero()), InputError);
  }
  CHECK_NOTHROW(export_frames(world, at, 30.0, kMaxExportFps, 0.0, 1.0));
  CHECK_THROWS_WITH(export_frames(world, at, 30.0, 30.0, 0.6, 0.2), Catch::Contains("empty"));
  CHECK_THROWS_WITH(export_frames(world, at, 30.0, 30.0, -0.1, 0.5), Catch::Contains("outside"));
  CHECK_THROWS_WITH(export_frames(world, at, 30.0, 30.0, 0.0, 1.1), Catch::Contains("outside"));
  CHECK_THROWS_AS(export_frames(world, at, 30.0, 30.0, nan, 0.5), InputError);
  CHECK_THROWS_AS(export_frames(world, at, 30.0, 30.0, 0.0, inf), InputError);
  CHECK_THROWS_WITH(export_frames(Eigen::MatrixXd(0, 3), Eigen::VectorXd(0), 30.0, 30.0, 0.0, 0.0),
                    Catch::Contains("no frames"));
  CHECK_THROWS_WITH(export_frames(world, rows_times(30, 1.0), 30.0, 30.0, 0.0, 0.5), Catch::Contains("must match"));
  CHECK_THROWS_AS(export_loop_frames(Eigen::MatrixXd::Zero(4, 4), rows_times(4, 1.0), 30.0, 30.0,
                                     Eigen::Vector2d::Zero()),
                  InputError);
}
