#include "engine/kinematics/resample.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "engine/kinematics/kinematics.h"
#include "tests/test_data.h"

using namespace mostyle;

namespace {

constexpr double kPositionTolerance = 1e-9;  // relative to the skeleton's size

double size_of(const Eigen::MatrixXd& p) {
  double lo = p.minCoeff(), hi = p.maxCoeff();
  return std::sqrt(3.0) * (hi - lo);
}

// One root joint with "Zrotation Xrotation Yrotation" and Xposition, a child at (1, 0, 0).
// Z angle and x position per frame as given.
Clip spinning_clip(const std::vector<double>& z, const std::vector<double>& x, double frame_time) {
  std::string text =
      "HIERARCHY\nROOT R\n{\nOFFSET 0 0 0\nCHANNELS 4 Xposition Zrotation Xrotation Yrotation\n"
      "JOINT C\n{\nOFFSET 1 0 0\nCHANNELS 0\nEnd Site\n{\nOFFSET 1 0 0\n}\n}\n}\nMOTION\nFrames: " +
      std::to_string(z.size()) + "\nFrame Time: " + std::to_string(frame_time) + "\n";
  for (size_t f = 0; f < z.size(); ++f)
    text += std::to_string(x[f]) + " " + std::to_string(z[f]) + " 0 0\n";
  return parse_bvh(text, "spin.bvh");
}

}  // namespace

TEST_CASE("resample 120 -> 30 takes every 4th frame", "[resample]") {
  const Clip clip = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  REQUIRE(clip.frame_time == 0.008333);  // 120.005 Hz, counted as 120
  REQUIRE(clip.fps() == 120.0);
  const Clip out = resample_clip(clip, 30);
  CHECK(out.frame_time == 1.0 / 30);
  CHECK(out.frames() == (clip.frames() - 1) / 4 + 1);
  const Eigen::MatrixXd p_in = joint_positions(clip);
  const Eigen::MatrixXd p_out = joint_positions(out);
  const double size = size_of(p_in);
  for (int f = 0; f < out.frames(); ++f) {
    REQUIRE((p_out.row(f) - p_in.row(4 * f)).cwiseAbs().maxCoeff() <= kPositionTolerance * size);
    // Root positions are copied, not recomputed.
    for (int c = 0; c < 3; ++c) REQUIRE(out.motion(f, c) == clip.motion(4 * f, c));
  }
}

TEST_CASE("resample 30 -> 120 -> 30 comes back", "[resample]") {
  const Clip clip = resample_clip(read_bvh_file(test::asset("motions/cmu142_walk_happy.bvh")), 30);
  const Clip up = resample_clip(clip, 120);
  CHECK(up.frames() == 4 * (clip.frames() - 1) + 1);
  const Clip down = resample_clip(up, 30);
  REQUIRE(down.frames() == clip.frames());
  const Eigen::MatrixXd p0 = joint_positions(clip);
  const double size = size_of(p0);
  CHECK((joint_positions(down) - p0).cwiseAbs().maxCoeff() <= kPositionTolerance * size);
  // In between, the upsampled motion stays between its neighbours: no joint leaves the segment
  // of its two source positions by more than a small fraction of the skeleton.
  const Eigen::MatrixXd pu = joint_positions(up);
  double worst = 0;
  for (int f = 0; f + 1 < clip.frames(); ++f) {
    for (int k = 1; k < 4; ++k) {
      const double w = k / 4.0;
      const Eigen::RowVectorXd linear = (1 - w) * p0.row(f) + w * p0.row(f + 1);
      worst = std::max(worst, (pu.row(4 * f + k) - linear).cwiseAbs().maxCoeff());
    }
  }
  CHECK(worst < 0.02 * size);
}

TEST_CASE("resample a 100 fps clip, worked by hand", "[resample]") {
  // Z turns 10 degrees a frame at 100 fps; x moves 1 a frame. 10 frames = 0.09 s.
  std::vector<double> z, x;
  for (int f = 0; f < 10; ++f) {
    z.push_back(10.0 * f);
    x.push_back(f);
  }
  const Clip clip = spinning_clip(z, x, 0.01);
  REQUIRE(clip.fps() == 100.0);
  SECTION("to 50 fps: every 2nd frame") {
    const Clip out = resample_clip(clip, 50);
    REQUIRE(out.frames() == 5);
    for (int f = 0; f < 5; ++f) {
      CHECK(out.motion(f, 0) == x[2 * f]);
      CHECK(out.motion(f, 1) == z[2 * f]);
    }
  }
  SECTION("to 30 fps: frame 1 at t = 1/30 s, source frame 3 1/3") {
    const Clip out = resample_clip(clip, 30);
    // floor(0.09 * 30) + 1 = 3 frames: t = 0, 1/30, 2/30 (source 0, 3.33, 6.67).
    REQUIRE(out.frames() == 3);
    // Slerp about one axis is linear in the angle: 33.33 degrees; x linear: 3.33.
    CHECK(out.motion(1, 0) == Approx(10.0 / 3).epsilon(1e-12));
    CHECK(out.motion(1, 1) == Approx(100.0 / 3).epsilon(1e-12));
    CHECK(out.motion(2, 1) == Approx(200.0 / 3).epsilon(1e-12));
    CHECK(out.motion(1, 2) == Approx(0).margin(1e-12));
    CHECK(out.motion(1, 3) == Approx(0).margin(1e-12));
    // The child at x + (cos 33.33, sin 33.33, 0).
    const Eigen::MatrixXd p = joint_positions(out);
    const double a = 100.0 / 3 * M_PI / 180;
    CHECK(p(1, 3) == Approx(10.0 / 3 + std::cos(a)).epsilon(1e-12));
    CHECK(p(1, 4) == Approx(std::sin(a)).epsilon(1e-12));
  }
}

TEST_CASE("resample slerps the short way across +-180 and unwraps", "[resample]") {
  // 170 then -170: 20 degrees apart through 180, not 340 through 0.
  const Clip clip = spinning_clip({170, -170, -150}, {0, 0, 0}, 1.0 / 30);
  const Clip out = resample_clip(clip, 60);
  REQUIRE(out.frames() == 5);
  CHECK(out.motion(1, 1) == Approx(180).epsilon(1e-12));
  CHECK(out.motion(2, 1) == Approx(190).epsilon(1e-12));  // -170, unwrapped
  CHECK(out.motion(3, 1) == Approx(200).epsilon(1e-12));
  CHECK(out.motion(4, 1) == Approx(210).epsilon(1e-12));
  const Eigen::MatrixXd p = joint_positions(out);
  CHECK(p(1, 3) == Approx(-1).epsilon(1e-12));  // the child at Rz(180)(1, 0, 0)
}

TEST_CASE("resample: bad rates, empty and one-frame clips", "[resample]") {
  const Clip clip = spinning_clip({0, 10}, {0, 1}, 0.1);
  CHECK_THROWS_AS(resample_clip(clip, 0), InputError);
  CHECK_THROWS_AS(resample_clip(clip, -30), InputError);
  CHECK_THROWS_AS(resample_clip(clip, std::nan("")), InputError);
  CHECK_THROWS_AS(resample_clip(clip, std::numeric_limits<double>::infinity()), InputError);
  // A 0.1 s clip at 1e12 fps would be 1e11 frames: refused before allocating.
  CHECK_THROWS_WITH(resample_clip(clip, 1e12), Catch::Contains("too many"));
  Clip bad = clip;
  bad.frame_time = 0;
  CHECK_THROWS_AS(resample_clip(bad, 30), InputError);

  const Clip one = resample_clip(spinning_clip({5}, {1}, 0.1), 120);
  CHECK(one.frames() == 1);
  CHECK(one.motion(0, 1) == 5);
  Clip none = clip;
  none.motion.resize(0, clip.motion.cols());
  CHECK(resample_clip(none, 30).frames() == 0);
}

TEST_CASE("sample_clip: fractional frames, clamped, at any frame time", "[resample]") {
  // Z turns 10 degrees a frame at 100 fps; x moves 1 a frame.
  std::vector<double> z, x;
  for (int f = 0; f < 10; ++f) {
    z.push_back(10.0 * f);
    x.push_back(f);
  }
  const Clip clip = spinning_clip(z, x, 0.01);
  Eigen::VectorXd at(6);
  at << 2.0, 2.5, 2.5, 0.25, -3.0, 20.0;  // repeated, backwards and out of range are all allowed
  const Clip out = sample_clip(clip, at, 24.0);
  REQUIRE(out.frames() == 6);
  CHECK(out.frame_time == 1.0 / 24.0);
  CHECK(out.skeleton.channel_count == clip.skeleton.channel_count);
  const double expected_x[] = {2, 2.5, 2.5, 0.25, 0, 9};
  const double expected_z[] = {20, 25, 25, 2.5, 0, 90};
  for (int f = 0; f < 6; ++f) {
    INFO("frame " << f << " at " << at[f]);
    CHECK(out.motion(f, 0) == Approx(expected_x[f]).margin(1e-12));
    CHECK(out.motion(f, 1) == Approx(expected_z[f]).margin(1e-12));
  }
  // The frames resample_clip would take give what it gives.
  const Clip half = resample_clip(clip, 30);
  Eigen::VectorXd same(half.frames());
  for (int f = 0; f < half.frames(); ++f) same[f] = f * 100.0 / 30.0;
  CHECK(sample_clip(clip, same, 30).motion == half.motion);
  // Errors.
  CHECK_THROWS_AS(sample_clip(clip, at, 0.0), InputError);
  CHECK_THROWS_AS(sample_clip(clip, at, std::nan("")), InputError);
  Eigen::VectorXd bad = at;
  bad[1] = std::nan("");
  CHECK_THROWS_AS(sample_clip(clip, bad, 30), InputError);
  Clip none = clip;
  none.motion.resize(0, clip.motion.cols());
  CHECK_THROWS_AS(sample_clip(none, at, 30), InputError);
  CHECK(sample_clip(clip, Eigen::VectorXd(0), 30).frames() == 0);
}

TEST_CASE("resample every shared file to 30 fps and 24 fps", "[resample]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  for (const std::string& path : test::shared_motions()) {
    INFO(path);
    const Clip clip = read_bvh_file(path);
    for (double fps : {30.0, 24.0}) {
      const Clip out = resample_clip(clip, fps);
      const double duration = (clip.frames() - 1) / clip.fps();
      CHECK(out.frames() == static_cast<int>(std::floor(duration * fps + 1e-9)) + 1);
      CHECK(out.motion.allFinite());
      // No jumps over 180 degrees between output frames in any rotation channel.
      for (const Joint& j : out.skeleton.joints) {
        for (size_t c = 0; c < j.channels.size(); ++c) {
          if (!is_rotation(j.channels[c])) continue;
          const int col = j.first_channel + static_cast<int>(c);
          for (int f = 1; f < out.frames(); ++f)
            REQUIRE(std::abs(out.motion(f, col) - out.motion(f - 1, col)) <= 180.0);
        }
      }
    }
  }
}

TEST_CASE("resample: only the chains of the joints asked for, the same values", "[resample]") {
  const Clip clip = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  // The left hand's chain and the right foot's; the fingers and the other limbs are not asked for.
  std::vector<int> asked;
  for (size_t j = 0; j < clip.skeleton.joints.size(); ++j) {
    const std::string& name = clip.skeleton.joints[j].name;
    if (name == "LeftHand" || name == "RightFoot") asked.push_back(static_cast<int>(j));
  }
  REQUIRE(asked.size() == 2);
  const Clip all = resample_clip(clip, 24);  // 120 -> 24 is every 5th frame: also try 36 (between frames)
  const Clip some = resample_clip(clip, 24, asked);
  CHECK(joint_positions(some, asked) == joint_positions(all, asked));
  const Clip between = resample_clip(clip, 36), between_some = resample_clip(clip, 36, asked);
  CHECK(joint_positions(between_some, asked) == joint_positions(between, asked));
  // A joint off the chains keeps zeros: nothing was sampled for it.
  for (const Joint& j : clip.skeleton.joints) {
    if (j.name != "RightHand" || j.channels.empty()) continue;
    CHECK(between_some.motion.middleCols(j.first_channel, j.channels.size()).isZero());
    CHECK_FALSE(between.motion.middleCols(j.first_channel, j.channels.size()).isZero());
  }
}
