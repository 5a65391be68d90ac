#include "engine/align/alignment_feature.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/base/error.h"

namespace mostyle {

const char* align_on_name(AlignOn on) {
  switch (on) {
    case AlignOn::kAuto: return "auto";
    case AlignOn::kLeftFoot: return "left-foot";
    case AlignOn::kFeet: return "feet";
    case AlignOn::kHands: return "hands";
    case AlignOn::kBody: return "body";
  }
  return "?";
}

AlignOn parse_align_on(const std::string& name) {
  for (AlignOn on : {AlignOn::kAuto, AlignOn::kLeftFoot, AlignOn::kFeet, AlignOn::kHands, AlignOn::kBody})
    if (name == align_on_name(on)) return on;
  throw InputError("expected an alignment feature auto, left-foot, feet, hands or body, found '" + name + "'");
}

double travel_speed(const CanonicalMotion& motion, double leg_length, double fps) {
  const Eigen::Index n = motion.ground.rows();
  if (n < 2 || !(leg_length > 0)) return 0.0;
  double path = 0.0;
  for (Eigen::Index t = 1; t < n; ++t) path += (motion.ground.row(t) - motion.ground.row(t - 1)).norm();
  return path / ((n - 1) / fps) / leg_length;
}

namespace {

// How much each joint moves: RMS distance from its mean position, over both takes.
std::vector<double> joint_motion(const CanonicalMotion& a, const CanonicalMotion& b) {
  const int joints = static_cast<int>(a.local.cols() / 3);
  std::vector<double> out(joints, 0.0);
  for (const Eigen::MatrixXd* m : {&a.local, &b.local}) {
    if (m->rows() == 0) continue;
    const Eigen::RowVectorXd mean = m->colwise().mean();
    const Eigen::VectorXd var = (m->rowwise() - mean).colwise().squaredNorm() / double(m->rows());
    for (int j = 0; j < joints; ++j) out[j] += 0.5 * (var[3 * j] + var[3 * j + 1] + var[3 * j + 2]);
  }
  for (double& v : out) v = std::sqrt(v);
  return out;
}

}  // namespace

AlignmentFeature alignment_feature(const CanonicalMotion& a, const CanonicalMotion& b, const FeatureJoints& joints,
                                   AlignOn on, double leg_length, double fps) {
  AlignmentFeature f;
  f.locomotion = travel_speed(a, leg_length, fps) >= kLocomotionLegsPerSecond &&
                 travel_speed(b, leg_length, fps) >= kLocomotionLegsPerSecond;
  f.on = on == AlignOn::kAuto ? (f.locomotion ? AlignOn::kLeftFoot : AlignOn::kBody) : on;
  auto need = [&](std::initializer_list<int> columns, const char* what) {
    for (int c : columns)
      if (c < 0) throw InputError(std::string("cannot align on the ") + what + ": the takes do not both have them");
    for (int c : columns) {
      f.columns.push_back(c);
      f.weights.push_back(1.0);
    }
  };
  switch (f.on) {
    case AlignOn::kLeftFoot: need({joints.left_ankle}, "left foot"); break;
    case AlignOn::kFeet: need({joints.left_ankle, joints.right_ankle}, "feet"); break;
    case AlignOn::kHands: need({joints.left_wrist, joints.right_wrist}, "hands"); break;
    case AlignOn::kAuto:
    case AlignOn::kBody: {
      const std::vector<double> motion = joint_motion(a, b);
      std::vector<int> order(motion.size());
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return motion[x] > motion[y]; });
      // The hips (column 0) are the canonical frame's origin: their bobbing says nothing of the
      // action's timing and must not set the scale for the joints that are used. Motion below a
      // millionth of the leg is rounding, not motion.
      double top = 0.0;
      for (int c : order)
        if (c != 0) {
          top = motion[c];
          break;
        }
      if (!(top > 1e-6 * leg_length)) top = 0.0;
      for (int c : order) {
        if (static_cast<int>(f.columns.size()) == kBodyMaxJoints || !(top > 0)) break;
        if (c == 0) continue;
        const double w = motion[c] / top;
        if (w < kBodyMinWeight) break;
        f.columns.push_back(c);
        f.weights.push_back(w);
      }
      if (f.columns.empty()) need({joints.left_ankle}, "left foot");  // nothing moves: the paper's choice
      break;
    }
  }
  const int c = static_cast<int>(f.columns.size());
  f.a.resize(a.local.rows(), 3 * c);
  f.b.resize(b.local.rows(), 3 * c);
  for (int k = 0; k < c; ++k) {
    f.a.middleCols(3 * k, 3) = f.weights[k] * a.local.middleCols(3 * f.columns[k], 3);
    f.b.middleCols(3 * k, 3) = f.weights[k] * b.local.middleCols(3 * f.columns[k], 3);
  }
  return f;
}

}  // namespace mostyle
