#include "engine/decompose/sparse_coding.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>

namespace mostyle {

namespace {

// Keeps the n largest |v_i| of one group (a row or column view), ties to the lower index.
template <typename Group>
void keep_largest_in_group(Group&& v, int n, std::vector<double>& magnitudes) {
  const int size = static_cast<int>(v.size());
  if (n >= size) return;
  if (n <= 0) {
    v.setZero();
    return;
  }
  magnitudes.resize(size);
  for (int i = 0; i < size; ++i) magnitudes[i] = std::abs(v[i]);
  // The n-th largest magnitude is the threshold: everything above it stays, and entries equal
  // to it fill the remaining places in index order.
  std::nth_element(magnitudes.begin(), magnitudes.begin() + (n - 1), magnitudes.end(),
                   std::greater<double>());
  const double threshold = magnitudes[n - 1];
  int above = 0;
  for (int i = 0; i < size; ++i) above += std::abs(v[i]) > threshold ? 1 : 0;
  int ties_left = n - above;
  for (int i = 0; i < size; ++i) {
    const double m = std::abs(v[i]);
    if (m > threshold) continue;
    if (m == threshold && ties_left > 0) {
      --ties_left;
      continue;
    }
    v[i] = 0.0;
  }
}

}  // namespace

void keep_largest(Eigen::MatrixXd& x, int nonzeros, SparseGroup group,
                  std::vector<double>& scratch) {
  if (group == SparseGroup::kColumn) {
    for (Eigen::Index j = 0; j < x.cols(); ++j) keep_largest_in_group(x.col(j), nonzeros, scratch);
  } else {
    for (Eigen::Index i = 0; i < x.rows(); ++i) keep_largest_in_group(x.row(i), nonzeros, scratch);
  }
}

void keep_connected(Eigen::Ref<Eigen::RowVectorXd> row, int nonzeros, const std::vector<std::vector<int>>& neighbours,
                    std::vector<char>& chosen) {
  const int joints = static_cast<int>(row.size() / 3);
  assert(static_cast<int>(neighbours.size()) == joints);
  const int budget = std::max(1, static_cast<int>(std::lround(nonzeros / 3.0)));
  auto energy = [&](int j) { return row.segment<3>(3 * j).squaredNorm(); };
  chosen.assign(static_cast<size_t>(joints), 0);
  int centre = 0;
  for (int j = 1; j < joints; ++j)
    if (energy(j) > energy(centre)) centre = j;
  chosen[static_cast<size_t>(centre)] = 1;
  for (int held = 1; held < budget; ++held) {
    int best = -1;
    double best_energy = 0.0;
    for (int j = 0; j < joints; ++j) {
      if (!chosen[static_cast<size_t>(j)]) continue;
      for (int n : neighbours[static_cast<size_t>(j)]) {
        if (chosen[static_cast<size_t>(n)]) continue;
        const double e = energy(n);
        if (e > best_energy || (e == best_energy && e > 0.0 && n < best)) {
          best = n;
          best_energy = e;
        }
      }
    }
    if (best < 0) break;
    chosen[static_cast<size_t>(best)] = 1;
  }
  for (int j = 0; j < joints; ++j)
    if (!chosen[static_cast<size_t>(j)]) row.segment<3>(3 * j).setZero();
}

std::vector<std::vector<int>> neighbours_of(const std::vector<int>& parents) {
  std::vector<std::vector<int>> out(parents.size());
  for (size_t j = 0; j < parents.size(); ++j) {
    const int p = parents[j];
    if (p < 0) continue;
    out[j].push_back(p);
    out[static_cast<size_t>(p)].push_back(static_cast<int>(j));
  }
  return out;
}

namespace {

// Column groups: every column steps with 1/L, L = ||gram||_2, then keeps its largest entries.
// Returns the iterations run.
int column_group_steps(const Eigen::MatrixXd& gram, const Eigen::MatrixXd& correlation, Eigen::MatrixXd& codes,
                       const SparseCodingOptions& options) {
  std::vector<double> scratch;
  scratch.reserve(static_cast<size_t>(std::max(codes.rows(), codes.cols())));
  Eigen::MatrixXd previous(codes.rows(), codes.cols());
  const double lipschitz =
      gram.rows() > 0
          ? Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff()
          : 0.0;
  const double step = lipschitz > 0.0 ? 1.0 / lipschitz : 0.0;
  Eigen::MatrixXd gradient(codes.rows(), codes.cols());
  int iteration = 0;
  while (iteration < options.max_iterations) {
    ++iteration;
    previous = codes;
    gradient.noalias() = gram * codes;
    gradient -= correlation;
    codes.noalias() -= step * gradient;
    keep_largest(codes, options.nonzeros, options.group, scratch);
    if (options.tolerance > 0.0 && (codes - previous).norm() <= options.tolerance * codes.norm()) break;
  }
  return iteration;
}

// Row groups: sweeps of block-coordinate descent, row i stepping with 1/gram(i, i) given the
// others, then kept sparse (connected on the skeleton when options.joint_neighbours is set).
// Returns the sweeps run.
int row_group_sweeps(const Eigen::MatrixXd& gram, const Eigen::MatrixXd& correlation, Eigen::MatrixXd& codes,
                     const SparseCodingOptions& options) {
  std::vector<double> scratch;
  scratch.reserve(static_cast<size_t>(std::max(codes.rows(), codes.cols())));
  Eigen::MatrixXd previous(codes.rows(), codes.cols());
  Eigen::RowVectorXd row(codes.cols()), target(codes.cols());
  std::vector<char> chosen;
  int iteration = 0;
  while (iteration < options.max_iterations) {
    ++iteration;
    previous = codes;
    for (Eigen::Index i = 0; i < codes.rows(); ++i) {
      const double curvature = gram(i, i);
      if (!(curvature > 0.0)) continue;  // a zero atom: the cost does not depend on this row
      // row_i - (1/G_ii) (G_i X - B_i): the gradient of row i at the current (partly updated) X.
      row.noalias() = gram.row(i) * codes;
      row = codes.row(i) - (row - correlation.row(i)) / curvature;
      if (options.joint_neighbours != nullptr) {
        // The row's cost is curvature/2 |row - target|^2 + const with target the unprojected
        // step: keep the projection only when it is at least as close as the current row (the
        // greedy connected projection is not exact), so the objective still never increases.
        target = row;
        keep_connected(row, options.nonzeros, *options.joint_neighbours, chosen);
        if ((row - target).squaredNorm() > (codes.row(i) - target).squaredNorm()) continue;
      } else {
        keep_largest_in_group(row, options.nonzeros, scratch);
      }
      codes.row(i) = row;
    }
    if (options.tolerance > 0.0 && (codes - previous).norm() <= options.tolerance * codes.norm()) break;
  }
  return iteration;
}

}  // namespace

int sparse_code_normal(const Eigen::MatrixXd& gram, const Eigen::MatrixXd& correlation,
                       Eigen::MatrixXd& codes, const SparseCodingOptions& options) {
  assert(gram.rows() == gram.cols());
  assert(correlation.rows() == gram.rows());
  assert(codes.rows() == correlation.rows() && codes.cols() == correlation.cols());

  // Step length (paper 3.3). The paper starts from the Newton step (D^T D)^-1 and, "to simplify
  // computation, select[s] the smallest step-length": along eigenvector i of D^T D the Newton
  // step has length 1/lambda_i, and the smallest is 1/lambda_max = 1/L with L = ||D^T D||_2.
  // Its printed 2/||D^T D|| is that rule for the unhalved cost ||Y - D X||^2 of eq. (3), whose
  // Hessian is 2 D^T D. Applied to the gradient D^T (D X - Y) of the halved cost used here, 2/L
  // is exactly the stability limit: the error along the top eigenvector is multiplied by
  // (1 - 2) = -1 each step and oscillates forever. With step 1/L_b, L_b the Lipschitz constant
  // of the block b being updated, each step minimizes the quadratic upper bound
  //   f(X_t) + <grad_b, X_b - X_t,b> + L_b/2 ||X_b - X_t,b||^2  >=  f(X)
  // over the sparse set, and the hard threshold is that bound's exact minimizer (the bound is
  // isotropic in the block). The objective therefore never increases once the iterate is
  // sparse: the decomposition's monotone objective rests on this.
  //
  // The blocks are the groups that share a budget:
  // - Column groups: the cost separates by columns and every column has Hessian D^T D, so all
  //   columns step together with 1/L, L = ||D^T D||_2 (the paper's x_j iteration).
  // - Row groups (a decomposition's components): rows are coupled through D^T D, and row i
  //   alone has Hessian (D^T D)_ii I. Rows are updated one after another (block-coordinate
  //   descent), each with its exact step 1/(D^T D)_ii, so each update is the exact best sparse
  //   row given the others. A shared step 1/L would shrink the entries outside a row's support
  //   by up to L/(D^T D)_ii (about k when the atoms overlap), which freezes the support at its
  //   initial guess; per-row steps let it move. Same cost per sweep: O(atoms^2 * signals).
  return options.group == SparseGroup::kColumn ? column_group_steps(gram, correlation, codes, options)
                                               : row_group_sweeps(gram, correlation, codes, options);
}

}  // namespace mostyle
