#include "engine/kinematics/limb_length.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "engine/base/error.h"
#include "tests/engine/synthetic_motion.h"

using namespace mostyle;
using mostyle::test::Random;

namespace {

constexpr double kRelativeExact = 1e-12;  // lengths and directions hold to rounding

Eigen::Vector3d joint(const Eigen::MatrixXd& m, int frame, int j) {
  return m.block<1, 3>(frame, 3 * j).transpose();
}

// apply_limb_lengths on a copy.
Eigen::MatrixXd with_limb_lengths(Eigen::MatrixXd positions, const std::vector<int>& parents,
                                  const std::vector<double>& lengths, const LimbLengthOptions& options = {}) {
  apply_limb_lengths(positions, parents, lengths, options);
  return positions;
}

// A 20-joint tree shaped like the major skeleton: hips, spine, chest, head, two arms, two legs.
const std::vector<int> kParents = {-1, 0, 1, 2,  2, 4, 5, 6,  2, 8, 9, 10,
                                   0,  12, 13, 14, 0, 16, 17, 18};

}  // namespace

TEST_CASE("limb lengths on a hand-worked 3-joint chain", "[limb_length]") {
  // root (0,0,0) -> a (0,2,0) with L = 1 -> b (3,2,0) with L = 2:
  // a = root + 1 * (0,1,0) = (0,1,0); b = a + 2 * (1,0,0) = (2,1,0).
  Eigen::MatrixXd p(1, 9);
  p << 0, 0, 0, 0, 2, 0, 3, 2, 0;
  apply_limb_lengths(p, {-1, 0, 1}, {0.0, 1.0, 2.0});
  Eigen::MatrixXd expected(1, 9);
  expected << 0, 0, 0, 0, 1, 0, 2, 1, 0;
  CHECK(p.isApprox(expected, 1e-15));

  // A branch: both children of the root move by their own bone only.
  Eigen::MatrixXd q(1, 12);
  q << 1, 1, 1, 1, 1, 4, 1, 1, -1, 1, 1, -5;
  const Eigen::MatrixXd r = with_limb_lengths(q, {-1, 0, 0, 2}, {0.0, 0.5, 1.0, 1.0});
  Eigen::MatrixXd expected_r(1, 12);
  expected_r << 1, 1, 1, 1, 1, 1.5, 1, 1, 0, 1, 1, -1;
  CHECK(r.isApprox(expected_r, 1e-15));
}

TEST_CASE("limb lengths become exact and bone directions are kept", "[limb_length]") {
  Random random(61);
  const int frames = 50, joints = 20;
  // A reference pose, and a distorted motion around it (as synthesis produces).
  const Eigen::MatrixXd reference = random.matrix(1, 3 * joints);
  const std::vector<double> lengths = bone_lengths(reference, kParents);
  Eigen::MatrixXd motion = reference.replicate(frames, 1) + 0.2 * random.matrix(frames, 3 * joints);
  const Eigen::MatrixXd before = motion;
  CHECK(max_bone_length_error(motion, kParents, lengths) > 0.01);

  apply_limb_lengths(motion, kParents, lengths);
  double longest = 0.0;
  for (double l : lengths) longest = std::max(longest, l);
  CHECK(max_bone_length_error(motion, kParents, lengths) <= kRelativeExact * longest);
  for (int f = 0; f < frames; ++f) {
    CHECK(joint(motion, f, 0) == joint(before, f, 0));  // the root stays
    for (int j = 1; j < joints; ++j) {
      const int p = kParents[static_cast<size_t>(j)];
      const Eigen::Vector3d after = joint(motion, f, j) - joint(motion, f, p);
      const Eigen::Vector3d original = joint(before, f, j) - joint(before, f, p);
      CAPTURE(f, j);
      CHECK(std::abs(after.norm() - lengths[static_cast<size_t>(j)]) <=
            kRelativeExact * lengths[static_cast<size_t>(j)]);
      CHECK(after.normalized().dot(original.normalized()) >= 1.0 - kRelativeExact);
    }
  }
  // Applying it again changes nothing beyond rounding.
  const Eigen::MatrixXd twice = with_limb_lengths(motion, kParents, lengths);
  CHECK((twice - motion).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("a bone with no direction takes the previous frame's, or the fallback", "[limb_length]") {
  // Joint 1 sits on the root in frames 0 and 2; frame 1 has it along +X.
  Eigen::MatrixXd p(3, 6);
  p << 0, 0, 0, 0, 0, 0,  //
      0, 0, 0, 5, 0, 0,   //
      1, 1, 1, 1, 1, 1;
  const std::vector<int> parents = {-1, 0};
  const std::vector<double> lengths = {0.0, 2.0};

  const Eigen::MatrixXd plain = with_limb_lengths(p, parents, lengths);
  CHECK(joint(plain, 0, 1) == Eigen::Vector3d(0, 2, 0));  // first frame: +Y
  CHECK(joint(plain, 1, 1) == Eigen::Vector3d(2, 0, 0));
  CHECK(joint(plain, 2, 1) == Eigen::Vector3d(3, 1, 1));  // previous frame's +X

  LimbLengthOptions options;
  options.fallback_pose.resize(6);
  options.fallback_pose << 0, 0, 0, 0, 0, -3;
  const Eigen::MatrixXd with_pose = with_limb_lengths(p, parents, lengths, options);
  CHECK(joint(with_pose, 0, 1) == Eigen::Vector3d(0, 0, -2));
  CHECK(max_bone_length_error(with_pose, parents, lengths) == 0.0);
}

TEST_CASE("bone lengths average over frames, the error is the worst deviation",
          "[limb_length]") {
  Eigen::MatrixXd p(2, 9);
  p << 0, 0, 0, 1, 0, 0, 1, 2, 0,  //
      0, 0, 0, 0, 3, 0, 0, 3, 4;
  const std::vector<int> parents = {-1, 0, 1};
  const std::vector<double> lengths = bone_lengths(p, parents);
  REQUIRE(lengths.size() == 3);
  CHECK(lengths[0] == 0.0);
  CHECK(lengths[1] == 2.0);  // (1 + 3) / 2
  CHECK(lengths[2] == 3.0);  // (2 + 4) / 2
  CHECK(max_bone_length_error(p, parents, lengths) == 1.0);
  CHECK(max_bone_length_error(p, parents, {0.0, 1.0, 2.0}) == 2.0);
}

TEST_CASE("limb-length functions reject bad skeletons", "[limb_length]") {
  Eigen::MatrixXd p = Eigen::MatrixXd::Ones(2, 9);
  const std::vector<int> parents = {-1, 0, 1};
  const std::vector<double> lengths = {0.0, 1.0, 1.0};
  CHECK_NOTHROW(apply_limb_lengths(p, parents, lengths));
  CHECK_THROWS_AS(apply_limb_lengths(p, {-1, 0}, lengths), InputError);
  CHECK_THROWS_AS(apply_limb_lengths(p, {-1, 2, 1}, lengths), InputError);  // child before parent
  CHECK_THROWS_AS(apply_limb_lengths(p, {-1, 0, -2}, lengths), InputError);
  CHECK_THROWS_AS(apply_limb_lengths(p, parents, {0.0, 1.0}), InputError);
  CHECK_THROWS_AS(apply_limb_lengths(p, parents, {0.0, -1.0, 1.0}), InputError);
  CHECK_THROWS_AS(apply_limb_lengths(p, parents, {0.0, std::nan(""), 1.0}), InputError);
  LimbLengthOptions options;
  options.fallback_pose = Eigen::RowVectorXd::Zero(6);
  CHECK_THROWS_AS(apply_limb_lengths(p, parents, lengths, options), InputError);
  options.fallback_pose.resize(0);
  options.degenerate_fraction = -1.0;
  CHECK_THROWS_AS(apply_limb_lengths(p, parents, lengths, options), InputError);
  CHECK_THROWS_AS(bone_lengths(Eigen::MatrixXd(0, 9), parents), InputError);
  CHECK_THROWS_AS(bone_lengths(p, {-1, 0}), InputError);
  CHECK_THROWS_AS(max_bone_length_error(p, parents, {0.0}), InputError);
}

TEST_CASE("a short bone leans on its previous direction instead of spinning round", "[limb_length]") {
  // A two-joint "hand" whose bone vector passes close by its parent: from (1, 0.05, 0) to
  // (-1, 0.05, 0) over 21 frames, so its own direction swings through half a turn in the two
  // frames around the middle. L = 1.
  const std::vector<int> parents = {-1, 0};
  const std::vector<double> lengths = {0.0, 1.0};
  Eigen::MatrixXd p(21, 6);
  for (int f = 0; f < 21; ++f) p.row(f) << 0, 0, 0, 1.0 - 0.1 * f, 0.05, 0;
  auto largest_turn = [&](const Eigen::MatrixXd& m) {
    double worst = 0;
    for (int f = 1; f < m.rows(); ++f)
      worst = std::max(worst, std::acos(std::clamp(joint(m, f, 1).normalized().dot(joint(m, f - 1, 1).normalized()), -1.0, 1.0)));
    return worst;
  };
  const Eigen::MatrixXd own = with_limb_lengths(p, parents, lengths);
  LimbLengthOptions lean;
  lean.short_fraction = 0.5;
  const Eigen::MatrixXd leaned = with_limb_lengths(p, parents, lengths, lean);
  INFO("largest turn per frame: " << largest_turn(own) << " rad on its own, " << largest_turn(leaned) << " leaning");
  CHECK(largest_turn(own) > 1.0);                          // half a turn within about two frames
  CHECK(largest_turn(leaned) < 0.9 * largest_turn(own));  // spread over more of the frames where it is short
  for (int f = 0; f < 21; ++f) CHECK(joint(leaned, f, 1).norm() == Approx(1.0).epsilon(kRelativeExact));
  // Long bones keep their own direction exactly.
  for (int f : {0, 1, 2, 3}) CHECK((joint(leaned, f, 1) - joint(own, f, 1)).norm() < kRelativeExact);
  lean.short_fraction = 1.5;
  CHECK_THROWS_AS(with_limb_lengths(p, parents, lengths, lean), InputError);
}

namespace {

// Paper 3.7 one frame and one bone at a time, as limb_length.h states it: the bone's own
// direction; a short bone turned from the previous frame's by (|bone| / short length)^2 of the
// angle; a bone with no direction the previous frame's (the first frame +y).
Eigen::MatrixXd limb_lengths_frame_by_frame(const Eigen::MatrixXd& original, const std::vector<int>& parents,
                                            const std::vector<double>& lengths, const LimbLengthOptions& options) {
  Eigen::MatrixXd out = original;
  for (Eigen::Index f = 0; f < original.rows(); ++f) {
    for (size_t j = 0; j < parents.size(); ++j) {
      const int p = parents[j];
      if (p < 0) continue;
      const double length = lengths[j];
      const Eigen::Vector3d bone = joint(original, int(f), int(j)) - joint(original, int(f), p);
      const double norm = bone.norm();
      Eigen::Vector3d direction = Eigen::Vector3d::UnitY();
      if (norm < options.short_fraction * length && f > 0) {
        const Eigen::Vector3d previous = (joint(out, int(f) - 1, int(j)) - joint(out, int(f) - 1, p)) / length;
        const double s = std::pow(norm / (options.short_fraction * length), 2);
        const double angle = norm > 0 ? std::acos(std::clamp(previous.dot(bone / norm), -1.0, 1.0)) : 0.0;
        direction = std::sin(angle) > 1e-9
                        ? Eigen::Vector3d((std::sin((1 - s) * angle) * previous + std::sin(s * angle) * (bone / norm)) /
                                          std::sin(angle))
                        : previous;
        direction.normalize();
      } else if (norm > options.degenerate_fraction * length) {
        direction = bone / norm;
      } else if (f > 0) {
        direction = (joint(out, int(f) - 1, int(j)) - joint(out, int(f) - 1, p)).normalized();
      }
      out.block<1, 3>(f, 3 * static_cast<Eigen::Index>(j)) =
          (joint(out, int(f), p) + length * direction).transpose();
    }
  }
  return out;
}

}  // namespace

TEST_CASE("limb lengths over a long motion with short and degenerate bones here and there match frame by frame",
          "[limb_length]") {
  // 301 frames (blocks of frames, four frames at a time where the processor can, and a ragged
  // end): some bones collapse onto their parents or shrink below the short length on single
  // frames, so that the frames around them are placed one at a time.
  Random random(7);
  const int frames = 301, joints = 20;
  const Eigen::MatrixXd reference = random.matrix(1, 3 * joints);
  const std::vector<double> lengths = bone_lengths(reference, kParents);
  Eigen::MatrixXd motion = reference.replicate(frames, 1) + 0.2 * random.matrix(frames, 3 * joints);
  for (int f = 3; f < frames; f += 37)
    for (int j : {5, 9, 13}) {
      const int p = kParents[static_cast<size_t>(j)];
      const double shrink = f % 2 == 0 ? 0.0 : 0.05;  // collapsed, or short
      motion.block<1, 3>(f, 3 * j) =
          motion.block<1, 3>(f, 3 * p) + shrink * (motion.block<1, 3>(f, 3 * j) - motion.block<1, 3>(f, 3 * p));
    }
  LimbLengthOptions options;
  options.short_fraction = 0.3;
  const Eigen::MatrixXd placed = with_limb_lengths(motion, kParents, lengths, options);
  const Eigen::MatrixXd expected = limb_lengths_frame_by_frame(motion, kParents, lengths, options);
  CHECK((placed - expected).cwiseAbs().maxCoeff() <= 1e-12);
  CHECK(max_bone_length_error(placed, kParents, lengths) <= 1e-12);
}
