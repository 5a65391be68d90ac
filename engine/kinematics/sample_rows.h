#pragma once
// Rows of a matrix (frames x channels) read at fractional rows, linearly interpolated: a take's
// poses at the frames a time warp or a mix's clock shows.
#include <Eigen/Core>

namespace mostyle {

// Rows of x (frames x channels) at fractional rows t (each clamped to [0, rows - 1]), linearly
// interpolated, into out (t.size() x channels; no allocation when it has that size). Throws
// InputError when x has no rows. O(t.size() x channels).
void sample_rows(const Eigen::MatrixXd& x, const Eigen::VectorXd& t, Eigen::MatrixXd& out);
Eigen::MatrixXd sample_rows(const Eigen::MatrixXd& x, const Eigen::VectorXd& t);

// The same with the rows and fractions worked out once for several matrices of `rows` rows:
// the alpha slider's path samples a few of them at every output frame.
struct RowSampler {
  Eigen::VectorXi row;    // K: the row before each sample time
  Eigen::VectorXd frac;   // K: how far towards the next row, 0..1
  void set(const Eigen::VectorXd& t, Eigen::Index rows);  // rows >= 1; no allocation once sized
  // out = x at the times (resized to K x x.cols()).
  void apply(const Eigen::MatrixXd& x, Eigen::MatrixXd& out) const;
  // out += weight times x at the times (out already K x x.cols()).
  void accumulate(const Eigen::MatrixXd& x, double weight, Eigen::MatrixXd& out) const;
};

}  // namespace mostyle
