#pragma once
// Comparing two clips' motion up to one similarity transform (the readers' accuracy measure):
// joint positions of the joints both have (by name), every frame, fitted with one rotation,
// uniform scale and translation (Umeyama 1991, Eigen::umeyama), errors as fractions of the
// first clip's height (kinematics/units.h guess_units).
#include <Eigen/Geometry>
#include <algorithm>
#include <string>
#include <vector>

#include "engine/base/clip.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/units.h"

namespace mostyle::test {

// Bounds on a read file's motion against its source, as fractions of the height.
constexpr double kMeanBound = 1e-3;
constexpr double kMaxBound = 5e-3;

struct MotionDifference {
  double mean = 0.0;  // mean distance after the fit / height
  double max = 0.0;   // largest distance after the fit / height
  double scale = 0.0; // the fit's scale (b's units to a's)
  int joints = 0;     // joints compared
  int frames = 0;     // frames compared (the shorter clip's)
};

// a's frame i against b's frame i, for min(frames) frames.
inline MotionDifference motion_difference(const Clip& a, const Clip& b) {
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < static_cast<int>(a.skeleton.joints.size()); ++i) {
    if (a.skeleton.joints[i].end_site) continue;
    const int j = b.skeleton.find(a.skeleton.joints[i].name);
    if (j >= 0) pairs.push_back({i, j});
  }
  MotionDifference d;
  d.joints = static_cast<int>(pairs.size());
  d.frames = std::min(a.frames(), b.frames());
  if (d.joints == 0 || d.frames == 0) return d;
  const Eigen::MatrixXd pa = joint_positions(a), pb = joint_positions(b);
  const Eigen::Index n = static_cast<Eigen::Index>(d.frames) * d.joints;
  Eigen::Matrix3Xd src(3, n), dst(3, n);
  for (int f = 0; f < d.frames; ++f)
    for (int k = 0; k < d.joints; ++k) {
      src.col(f * d.joints + k) = pb.block<1, 3>(f, 3 * pairs[k].second).transpose();
      dst.col(f * d.joints + k) = pa.block<1, 3>(f, 3 * pairs[k].first).transpose();
    }
  const Eigen::Matrix4d t = Eigen::umeyama(src, dst, true);
  d.scale = t.block<3, 3>(0, 0).determinant();
  d.scale = std::cbrt(d.scale);
  const Eigen::Matrix3Xd fitted = (t.block<3, 3>(0, 0) * src).colwise() + t.block<3, 1>(0, 3);
  const Eigen::VectorXd err = (fitted - dst).colwise().norm();
  const double height = guess_units(a).height;
  d.mean = err.mean() / height;
  d.max = err.maxCoeff() / height;
  return d;
}

}  // namespace mostyle::test
