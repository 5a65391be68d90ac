#include "engine/prepare/retarget.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

#include "engine/base/error.h"
#include "engine/kinematics/limb_length.h"

namespace mostyle {

double leg_length(const std::vector<double>& lengths, const int (&leg_joints)[6]) {
  // Thigh = length of the knee's bone, shin = length of the ankle's bone.
  return 0.5 * (lengths[leg_joints[1]] + lengths[leg_joints[2]] + lengths[leg_joints[4]] +
                lengths[leg_joints[5]]);
}

Eigen::MatrixXd retarget_positions(const Eigen::MatrixXd& world_b, const std::vector<int>& parents,
                                   const std::vector<double>& lengths_a, double leg_a, double leg_b) {
  if (!(leg_a > 0) || !(leg_b > 0) || !std::isfinite(leg_a / leg_b))
    throw InputError("cannot retarget: a take has legs of zero length");
  // A uniform scale keeps every bone direction; the limb pass then fixes each length exactly.
  Eigen::MatrixXd out = world_b * (leg_a / leg_b);
  apply_limb_lengths(out, parents, lengths_a);
  return out;
}

namespace {

Eigen::Vector3d bone(const Eigen::MatrixXd& w, Eigen::Index frame, int child, int parent) {
  return (w.block<1, 3>(frame, 3 * child) - w.block<1, 3>(frame, 3 * parent)).transpose();
}

// Below this determinant of the normalized cross-covariance (at most 3^-1.5, an isotropic one),
// the groups' bones are near a plane or a line, or the best fit a reflection: the SVD decides.
constexpr double kPolarMinDeterminant = 1e-6;
// Newton steps at most, and the change (largest entry) at which it has converged: quadratic
// convergence then takes the next step to rounding.
constexpr int kPolarSteps = 30;
constexpr double kPolarConverged = 1e-10;

// The rotation R minimizing sum |R from_i - to_i|^2 (Kabsch), a proper rotation: the orthogonal
// factor of h^T's polar decomposition (h = sum from_i to_i^T), by Newton's iteration scaled by the
// determinant (Higham; Byers and Xu), a few 3x3 inverses where a Jacobi SVD of every frame's group
// was an eighth of preparing a pair; the SVD where the determinant is small or negative.
Eigen::Matrix3d best_rotation(const std::vector<Eigen::Vector3d>& from,
                              const std::vector<Eigen::Vector3d>& to) {
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < from.size(); ++i) h += from[i] * to[i].transpose();
  const double size = h.norm();
  if (!(size > 0.0)) return Eigen::Matrix3d::Identity();
  Eigen::Matrix3d x = h.transpose() / size;
  double det = x.determinant();
  if (det > kPolarMinDeterminant) {
    for (int step = 0; step < kPolarSteps; ++step) {
      const double g = std::cbrt(1.0 / det);
      const Eigen::Matrix3d next = 0.5 * (g * x + x.inverse().transpose() / g);
      const double change = (next - x).cwiseAbs().maxCoeff();
      x = next;
      if (change < kPolarConverged) return 0.5 * (x + x.inverse().transpose());
      det = x.determinant();
    }
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0) d(2, 2) = -1.0;
  return svd.matrixV() * d * svd.matrixU().transpose();
}

}  // namespace

// A take's mean shape of one joint group: every frame's group turned back onto frame 0's
// (least squares), averaged.
std::vector<Eigen::Vector3d> mean_group_shape(const Eigen::MatrixXd& world, int joint,
                                              const std::vector<int>& group) {
  const size_t k = group.size();
  std::vector<Eigen::Vector3d> first(k), shape(k, Eigen::Vector3d::Zero()), current(k);
  for (size_t i = 0; i < k; ++i) first[i] = bone(world, 0, group[i], joint);
  for (Eigen::Index f = 0; f < world.rows(); ++f) {
    for (size_t i = 0; i < k; ++i) current[i] = bone(world, f, group[i], joint);
    const Eigen::Matrix3d r = best_rotation(first, current);
    for (size_t i = 0; i < k; ++i) shape[i] += r.transpose() * current[i];
  }
  for (Eigen::Vector3d& v : shape) v /= static_cast<double>(world.rows());
  return shape;
}

void adopt_group_shapes(Eigen::MatrixXd& world_b, const Eigen::MatrixXd& world_a,
                        const std::vector<int>& parents) {
  const int joints = static_cast<int>(parents.size());
  if (world_a.rows() == 0 || world_b.rows() == 0) return;
  std::vector<std::vector<int>> children(joints);
  for (int j = 0; j < joints; ++j)
    if (parents[j] >= 0) children[parents[j]].push_back(j);
  for (int j = 0; j < joints; ++j) {
    const std::vector<int>& group = children[j];
    const size_t k = group.size();
    if (k < 2) continue;
    const std::vector<Eigen::Vector3d> shape_a = mean_group_shape(world_a, j, group);
    const std::vector<Eigen::Vector3d> shape_b = mean_group_shape(world_b, j, group);
    // A's mean shape in the orientation of B's: shape_a ~ q shape_b.
    const Eigen::Matrix3d q = best_rotation(shape_b, shape_a);
    std::vector<Eigen::Vector3d> target_shape(k);
    for (size_t i = 0; i < k; ++i) target_shape[i] = q.transpose() * shape_a[i];
    // Which group member each joint's subtree hangs from (parents come first).
    std::vector<int> owner(joints, -1);
    for (size_t i = 0; i < k; ++i) owner[group[i]] = static_cast<int>(i);
    for (int d = 0; d < joints; ++d)
      if (owner[d] < 0 && parents[d] >= 0 && parents[d] != j && owner[parents[d]] >= 0) owner[d] = owner[parents[d]];
    // Per frame, B's group is r (shape_b + deviation): keep r and the deviation (a shrug is
    // style), swap B's mean shape for A's. With A's own take as B nothing changes.
    std::vector<Eigen::Vector3d> current(k), delta(k);
    for (Eigen::Index f = 0; f < world_b.rows(); ++f) {
      for (size_t i = 0; i < k; ++i) current[i] = bone(world_b, f, group[i], j);
      const Eigen::Matrix3d r = best_rotation(shape_b, current);
      for (size_t i = 0; i < k; ++i) delta[i] = r * (target_shape[i] - shape_b[i]);
      for (int d = 0; d < joints; ++d)
        if (owner[d] >= 0) world_b.block<1, 3>(f, 3 * d) += delta[owner[d]].transpose();
    }
  }
}

}  // namespace mostyle
