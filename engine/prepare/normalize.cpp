#include "engine/prepare/normalize.h"

#include <cmath>

namespace mostyle {

Normalization fit_normalization(const Eigen::MatrixXd& local_a, const Eigen::MatrixXd& local_b) {
  Normalization n;
  n.mean_a = local_a.colwise().mean();
  n.mean_b = local_b.colwise().mean();
  const double sum = (local_a.rowwise() - n.mean_a).squaredNorm() +
                     (local_b.rowwise() - n.mean_b).squaredNorm();
  const double count = static_cast<double>(local_a.size() + local_b.size());
  n.scale = count > 0 ? std::sqrt(sum / count) : 1.0;
  if (!(n.scale > 0) || !std::isfinite(n.scale)) n.scale = 1.0;
  return n;
}

Eigen::MatrixXd normalize(const Eigen::MatrixXd& local, const Eigen::RowVectorXd& mean, double scale) {
  return (local.rowwise() - mean) / scale;
}

}  // namespace mostyle
