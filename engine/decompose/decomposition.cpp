#include "engine/decompose/decomposition.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engine/base/clock.h"
#include "engine/base/error.h"
#include "engine/decompose/sparse_coding.h"

namespace mostyle {

namespace {

using Clock = std::chrono::steady_clock;

double nonzero_fraction(const Eigen::MatrixXd& c) {
  if (c.size() == 0) return 0.0;
  return static_cast<double>((c.array() != 0.0).count()) / static_cast<double>(c.size());
}

// Paper 3.4 "Initialization". Picks, k times, the joint whose residual trajectory (its three
// columns) has the most energy sum(X^2), and factors that frames x 3 trajectory by its best
// rank-1 approximation w v^T: w is the new weight column and v that joint's component entries.
// The rank-1 factor comes from the top eigenvector of the 3 x 3 Gram matrix T^T T, which is the
// SVD's right singular vector at O(frames) cost.
// When the budget allows more than the joint's 3 channels, the rest of it goes to the other
// channels that w explains best (their least-squares coefficients R^T w / |w|^2, largest
// first): the component starts as the best sparse row for w that contains the joint, like
// SPLOCS's init grows a component around its vertex. Subtracting it removes the signal from
// every channel it explains, so the next pick is another part of the body rather than a
// neighbour moving with the same signal (which left whole limbs to one component and others to
// none, a local minimum the alternation could not leave).
// r: frames x 3N, in: x, out: the residual x - w c. w: frames x k, c: k x 3N, both zeroed first.
// With neighbours (local components), the component instead grows from the joint through
// neighbouring joints, whole joints at a time (keep_connected on those coefficients).
void greedy_init(int keep, const std::vector<std::vector<int>>* neighbours, Eigen::MatrixXd& r, Eigen::MatrixXd& w,
                 Eigen::MatrixXd& c) {
  const Eigen::Index joints = r.cols() / 3;
  w.setZero();
  c.setZero();
  Eigen::VectorXd energy(joints);
  const auto update_energy = [&] {
    for (Eigen::Index j = 0; j < joints; ++j) energy[j] = r.middleCols(3 * j, 3).squaredNorm();
  };
  update_energy();
  std::vector<double> scratch;
  std::vector<char> chosen;
  Eigen::MatrixXd others(r.cols(), 1);

  for (Eigen::Index component = 0; component < w.cols(); ++component) {
    Eigen::Index joint = 0;
    energy.maxCoeff(&joint);  // the first maximum: deterministic
    const auto trajectory = r.middleCols(3 * joint, 3);
    const Eigen::Matrix3d gram = trajectory.transpose() * trajectory;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(gram);
    Eigen::MatrixXd v = eigen.eigenvectors().col(2);  // eigenvalues ascend: the largest is last
    // (v is a 3 x 1 matrix so keep_largest can take it)
    // Fix the SVD's sign ambiguity so the result does not depend on the eigen solver's choice.
    Eigen::Index largest = 0;
    v.col(0).cwiseAbs().maxCoeff(&largest);
    if (v(largest, 0) < 0.0) v = -v;
    // With fewer than 3 channels per component the init must already be that sparse, so the
    // first sparse-coding step starts feasible (which keeps the objective monotone).
    if (keep < 3) keep_largest(v, keep, SparseGroup::kColumn, scratch);
    // Least-squares weights for the fixed direction v: w = T v / (v^T v); for the unit
    // singular vector this is the rank-1 SVD's sigma * u.
    Eigen::VectorXd weight = trajectory * v / v.squaredNorm();
    // P_v: the weight column is scaled to max |w| = 1 and the component inversely.
    const double scale = weight.cwiseAbs().maxCoeff();
    if (scale > 0.0) {
      weight /= scale;
      v *= scale;
    }
    w.col(component) = weight;
    c.block<1, 3>(component, 3 * joint) = v.col(0).transpose();
    if (keep > 3 && scale > 0.0) {
      others.noalias() = r.transpose() * weight;
      others /= weight.squaredNorm();
      if (neighbours != nullptr) {
        // Grown from this joint: its own entries are the largest so it is the centre.
        Eigen::RowVectorXd row = others.col(0).transpose();
        row.segment<3>(3 * joint).setConstant(std::numeric_limits<double>::infinity());  // the centre
        keep_connected(row, keep, *neighbours, chosen);
        for (Eigen::Index j = 0; j < r.cols(); ++j)
          if (row[j] != 0.0 && (j < 3 * joint || j >= 3 * joint + 3)) c(component, j) = others(j, 0);
      } else {
        others.block<3, 1>(3 * joint, 0).setZero();
        keep_largest(others, keep - 3, SparseGroup::kColumn, scratch);
        for (Eigen::Index j = 0; j < r.cols(); ++j) {
          if (others(j, 0) != 0.0) c(component, j) = others(j, 0);
        }
      }
    }
    for (Eigen::Index j = 0; j < r.cols(); ++j) {
      const double value = c(component, j);
      if (value != 0.0) r.col(j).noalias() -= value * weight;
    }
    update_energy();
  }
}

// r = x - w c, using the sparsity of c: O(frames * nnz(c)) instead of a dense product.
void residual(const Eigen::MatrixXd& x, const Eigen::MatrixXd& w, const Eigen::MatrixXd& c,
              Eigen::MatrixXd& r) {
  r = x;
  for (Eigen::Index j = 0; j < c.cols(); ++j) {
    for (Eigen::Index k = 0; k < c.rows(); ++k) {
      const double value = c(k, j);
      if (value != 0.0) r.col(j).noalias() -= value * w.col(k);
    }
  }
}

// Paper 3.4 "Weights optimization": for each component k in turn, with the others fixed,
//   w_k = P_v(((R + w_k c_k) c_k^T) / (c_k c_k^T)),   R = X - W C,
// the exact least-squares minimizer for that column (so the objective cannot increase), then
// P_v scales w_k to max |w| = 1 and c_k by the inverse, leaving W C unchanged. R is kept up to
// date on c_k's support only, which is all that changes: O(frames * nnz(c_k)) per component.
void update_weights(Eigen::MatrixXd& r, Eigen::MatrixXd& w, Eigen::MatrixXd& c,
                    Eigen::VectorXd& new_weight, std::vector<Eigen::Index>& support) {
  for (Eigen::Index k = 0; k < w.cols(); ++k) {
    support.clear();
    double norm2 = 0.0;
    for (Eigen::Index j = 0; j < c.cols(); ++j) {
      const double value = c(k, j);
      if (value != 0.0) {
        support.push_back(j);
        norm2 += value * value;
      }
    }
    if (norm2 == 0.0) continue;  // an empty component: no weight can change the fit
    new_weight.noalias() = norm2 * w.col(k);
    for (Eigen::Index j : support) new_weight.noalias() += c(k, j) * r.col(j);
    new_weight /= norm2;
    // R loses (w_new - w_old) c_k on the support.
    w.col(k) -= new_weight;  // now -(w_new - w_old)
    for (Eigen::Index j : support) r.col(j).noalias() += c(k, j) * w.col(k);
    const double scale = new_weight.cwiseAbs().maxCoeff();
    if (scale > 0.0) {
      w.col(k).noalias() = new_weight / scale;
      c.row(k) *= scale;
    } else {
      w.col(k) = new_weight;
    }
  }
}

Decomposition run_decomposition(const Eigen::MatrixXd& x, const DecompositionOptions& options,
                                JobControl* control, float progress_begin, float progress_end) {
  const Clock::time_point start = Clock::now();
  options.Validate(x);
  const Eigen::Index frames = x.rows();
  const int channels = static_cast<int>(x.cols());
  const int k = options.components;
  const int keep = options.NonzerosPerComponent(channels);

  Decomposition result;
  Eigen::MatrixXd& w = result.weights;
  Eigen::MatrixXd& c = result.components;
  w.resize(frames, k);
  c.resize(k, channels);
  Eigen::MatrixXd r = x;
  const std::vector<std::vector<int>> neighbours = neighbours_of(options.locality_parents);
  const std::vector<std::vector<int>>* local = options.locality_parents.empty() ? nullptr : &neighbours;
  greedy_init(keep, local, r, w, c);
  double objective = r.squaredNorm();
  result.objective_history.reserve(static_cast<size_t>(options.max_iterations) + 1);
  result.objective_history.push_back(objective);

  // Paper 3.4 "Components optimization": a few warm-started sweeps of the sparse coding of 3.3
  // with D = W and one budget per component row of C, on the normal equations (W^T W, W^T X)
  // so a sweep costs O(k^2 * 3N) and only W^T X touches every frame.
  SparseCodingOptions coding;
  coding.nonzeros = keep;
  coding.group = SparseGroup::kRow;
  coding.max_iterations = options.sparse_coding_iterations;
  coding.tolerance = 0.0;
  coding.joint_neighbours = local;

  Eigen::MatrixXd gram(k, k);
  Eigen::MatrixXd correlation(k, channels);
  Eigen::VectorXd new_weight(frames);
  std::vector<Eigen::Index> support;
  support.reserve(static_cast<size_t>(channels));

  const float progress_span = progress_end - progress_begin;
  report_progress(control, progress_begin);
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    check_cancel(control);
    update_weights(r, w, c, new_weight, support);
    gram.noalias() = w.transpose() * w;
    correlation.noalias() = w.transpose() * x;
    sparse_code_normal(gram, correlation, c, coding);
    residual(x, w, c, r);

    const double previous = objective;
    objective = r.squaredNorm();
    result.objective_history.push_back(objective);
    result.iterations = iteration + 1;
    report_progress(control, progress_begin + progress_span * static_cast<float>(iteration + 1) /
                                                  static_cast<float>(options.max_iterations));
    if (objective == 0.0 || std::abs(previous - objective) < options.tolerance * previous) {
      result.converged = true;
      break;
    }
  }
  report_progress(control, progress_end);

  if (!w.allFinite() || !c.allFinite() || !std::isfinite(objective)) {
    throw std::runtime_error(
        "decomposition: the result holds a NaN or infinite value (numerical trouble).");
  }
  result.objective = objective;
  result.rmse = std::sqrt(objective / static_cast<double>(x.size()));
  result.nonzero_fraction = nonzero_fraction(c);
  result.elapsed_ms = ms_since(start);
  return result;
}

}  // namespace

void DecompositionOptions::Validate(const Eigen::MatrixXd& x) const {
  if (x.rows() == 0 || x.cols() == 0) {
    throw InputError("decomposition: the motion matrix is empty (" + std::to_string(x.rows()) +
                     " frames x " + std::to_string(x.cols()) + " channels).");
  }
  if (x.cols() % 3 != 0) {
    throw InputError("decomposition: the motion matrix has " + std::to_string(x.cols()) +
                     " channels, which is not 3 per joint.");
  }
  if (components < 1 || components > x.cols()) {
    throw InputError("decomposition: the number of components must be between 1 and " +
                     std::to_string(x.cols()) + " (3 x joints), got " +
                     std::to_string(components) + ".");
  }
  if (!(sparsity > 0.0 && sparsity <= 1.0)) {
    throw InputError("decomposition: the sparsity must be in (0, 1], got " +
                     std::to_string(sparsity) + ".");
  }
  if (max_iterations < 0) {
    throw InputError("decomposition: max_iterations must be >= 0, got " +
                     std::to_string(max_iterations) + ".");
  }
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance)) {
    throw InputError("decomposition: the tolerance must be a finite number >= 0, got " +
                     std::to_string(tolerance) + ".");
  }
  if (sparse_coding_iterations < 1) {
    throw InputError("decomposition: sparse_coding_iterations must be >= 1, got " +
                     std::to_string(sparse_coding_iterations) + ".");
  }
  if (!x.allFinite()) {
    throw InputError("decomposition: the motion matrix holds a NaN or infinite value.");
  }
  if (!locality_parents.empty()) {
    if (static_cast<Eigen::Index>(locality_parents.size()) * 3 != x.cols())
      throw InputError("decomposition: the skeleton for local components has " + std::to_string(locality_parents.size()) +
                       " joints, the motion matrix " + std::to_string(x.cols() / 3) + ".");
    for (size_t j = 0; j < locality_parents.size(); ++j)
      if (locality_parents[j] < -1 || locality_parents[j] >= static_cast<int>(locality_parents.size()) ||
          locality_parents[j] == static_cast<int>(j))
        throw InputError("decomposition: joint " + std::to_string(j) + " of the skeleton for local components has "
                         "parent " + std::to_string(locality_parents[j]) + ".");
  }
}

int DecompositionOptions::NonzerosPerComponent(int channels) const {
  const int rounded = static_cast<int>(std::lround(sparsity * channels));
  return std::clamp(rounded, 1, std::max(channels, 1));
}

Decomposition decompose(const Eigen::MatrixXd& x, const DecompositionOptions& options,
                        JobControl* control) {
  return run_decomposition(x, options, control, 0.0f, 1.0f);
}

namespace detail {
Decomposition decompose_part(const Eigen::MatrixXd& x, const DecompositionOptions& options,
                             JobControl* control, float progress_begin, float progress_end) {
  return run_decomposition(x, options, control, progress_begin, progress_end);
}
}  // namespace detail

StackedDecomposition decompose_stacked(const std::vector<const Eigen::MatrixXd*>& takes,
                                       const DecompositionOptions& options, JobControl* control) {
  const Clock::time_point start = Clock::now();
  if (takes.empty()) throw InputError("a shared decomposition needs at least one take");
  Eigen::Index rows = 0;
  for (size_t i = 0; i < takes.size(); ++i) {
    try {
      options.Validate(*takes[i]);
    } catch (const InputError& e) {
      throw InputError("take " + std::to_string(i + 1) + ": " + e.what());
    }
    if (takes[i]->cols() != takes[0]->cols())
      throw InputError("shared decomposition: take 1 has " + std::to_string(takes[0]->cols()) + " channels and take " +
                       std::to_string(i + 1) + " has " + std::to_string(takes[i]->cols()) +
                       "; all need the same joints.");
    rows += takes[i]->rows();
  }
  Eigen::MatrixXd stacked(rows, takes[0]->cols());
  Eigen::Index row = 0;
  for (const Eigen::MatrixXd* x : takes) {
    stacked.middleRows(row, x->rows()) = *x;
    row += x->rows();
  }
  Decomposition d = run_decomposition(stacked, options, control, 0.0f, 1.0f);

  StackedDecomposition result;
  row = 0;
  for (const Eigen::MatrixXd* x : takes) {
    result.weights.push_back(d.weights.middleRows(row, x->rows()));
    row += x->rows();
  }
  result.components = std::move(d.components);
  for (size_t i = 0; i < takes.size(); ++i)
    result.rmse.push_back(std::sqrt((*takes[i] - result.weights[i] * result.components).squaredNorm() /
                                    static_cast<double>(takes[i]->size())));
  result.iterations = d.iterations;
  result.converged = d.converged;
  result.objective = d.objective;
  result.nonzero_fraction = d.nonzero_fraction;
  result.objective_history = std::move(d.objective_history);
  result.elapsed_ms = ms_since(start);
  return result;
}

}  // namespace mostyle
