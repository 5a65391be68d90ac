#pragma once
// One joint of a positions matrix (rows: frames, columns: x y z of each joint in turn), read and
// written as a point: the post-processing passes move joints one at a time.
#include <Eigen/Core>

namespace mostyle {

// Joint `joint`'s position at `row` of m (any Eigen matrix or block, 3 columns a joint).
template <typename Matrix>
Eigen::Vector3d joint_at(const Matrix& m, Eigen::Index row, int joint) {
  return Eigen::Vector3d(m(row, 3 * joint), m(row, 3 * joint + 1), m(row, 3 * joint + 2));
}

// Sets joint `joint`'s position at `row` of m to v.
template <typename Matrix>
void set_joint(Matrix& m, Eigen::Index row, int joint, const Eigen::Vector3d& v) {
  m(row, 3 * joint) = v.x();
  m(row, 3 * joint + 1) = v.y();
  m(row, 3 * joint + 2) = v.z();
}

}  // namespace mostyle
