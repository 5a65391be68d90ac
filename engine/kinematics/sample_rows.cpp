#include "engine/kinematics/sample_rows.h"

#include <algorithm>

#include "engine/base/error.h"

namespace mostyle {

void sample_rows(const Eigen::MatrixXd& x, const Eigen::VectorXd& t, Eigen::MatrixXd& out) {
  if (x.rows() == 0) throw InputError("cannot sample a motion with no frames");
  out.resize(t.size(), x.cols());
  // Column by column: the matrices are column-major, so both sides are read and written in
  // order; the row and fraction are recomputed per column, cheaper than strided access.
  const Eigen::Index last = x.rows() - 1;
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    const double* in = x.col(c).data();
    double* o = out.col(c).data();
    for (Eigen::Index k = 0; k < t.size(); ++k) {
      const double at = std::clamp(t[k], 0.0, static_cast<double>(last));
      const Eigen::Index i = std::min<Eigen::Index>(static_cast<Eigen::Index>(at), std::max<Eigen::Index>(last - 1, 0));
      const double f = at - static_cast<double>(i);
      o[k] = last == 0 ? in[0] : in[i] + f * (in[i + 1] - in[i]);
    }
  }
}

void RowSampler::set(const Eigen::VectorXd& t, Eigen::Index rows) {
  if (rows < 1) throw InputError("cannot sample a motion with no frames");
  row.resize(t.size());
  frac.resize(t.size());
  const Eigen::Index last = rows - 1;
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    const double at = std::clamp(t[k], 0.0, static_cast<double>(last));
    const Eigen::Index i = std::min<Eigen::Index>(static_cast<Eigen::Index>(at), std::max<Eigen::Index>(last - 1, 0));
    row[k] = static_cast<int>(i);
    frac[k] = last == 0 ? 0.0 : at - static_cast<double>(i);
  }
}

void RowSampler::apply(const Eigen::MatrixXd& x, Eigen::MatrixXd& out) const {
  const Eigen::Index n = row.size();
  out.resize(n, x.cols());
  const bool single = x.rows() == 1;
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    const double* in = x.col(c).data();
    double* o = out.col(c).data();
    for (Eigen::Index k = 0; k < n; ++k) {
      const double* p = in + row[k];
      o[k] = single ? p[0] : p[0] + frac[k] * (p[1] - p[0]);
    }
  }
}

void RowSampler::accumulate(const Eigen::MatrixXd& x, double weight, Eigen::MatrixXd& out) const {
  const Eigen::Index n = row.size();
  const bool single = x.rows() == 1;
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    const double* in = x.col(c).data();
    double* o = out.col(c).data();
    for (Eigen::Index k = 0; k < n; ++k) {
      const Eigen::Index i = row[k];
      const double f = single ? 0.0 : frac[k];
      o[k] += weight * (in[i] + f * (in[i + (single ? 0 : 1)] - in[i]));
    }
  }
}

Eigen::MatrixXd sample_rows(const Eigen::MatrixXd& x, const Eigen::VectorXd& t) {
  Eigen::MatrixXd out;
  sample_rows(x, t, out);
  return out;
}

}  // namespace mostyle
