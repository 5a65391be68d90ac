#pragma once
// Normalization (DESIGN.md 5): mean pose per take, one global scale shared by both takes.
#include <Eigen/Core>

namespace mostyle {

struct Normalization {
  Eigen::RowVectorXd mean_a;  // 1 x 3J, file units
  Eigen::RowVectorXd mean_b;  // 1 x 3J, file units
  double scale = 1.0;         // std of all centered entries of both takes, file units
};

// local_a: Fa x 3J, local_b: Fb x 3J. Per-dimension std would divide by zero on constant
// channels (the hips' x and z in the canonical frame), so one global scale is used. A scale
// of zero (no motion at all) becomes 1.
Normalization fit_normalization(const Eigen::MatrixXd& local_a, const Eigen::MatrixXd& local_b);

// (local - mean) / scale, and back.
Eigen::MatrixXd normalize(const Eigen::MatrixXd& local, const Eigen::RowVectorXd& mean, double scale);

}  // namespace mostyle
