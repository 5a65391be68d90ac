#include "engine/align/slope_dtw.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>

#include "engine/align/dtw.h"
#include "engine/base/error.h"

// The recurrence is the symmetric slope-constrained one of Sakoe and Chiba (1978), with steps
// (1, 1), (1, k) and (k, 1) for k up to max_slope, each weighted by the frames it covers so a
// path's weight is the number of frames of both takes it matches. Open ends follow the
// subsequence idea (free start and end) with a per-frame penalty for what is left out, which
// makes the comparison of paths of different lengths fair: with local costs c - penalty the
// objective is a plain minimum-sum path that may start and end at any cell.
//
// Rows run one after the other with a ring of max_slope + 1 cost rows. Back-pointers take 4 bits
// a cell; when the whole grid does not fit the budget, a first pass keeps checkpoint rows every
// R rows, and the traceback recomputes one segment of R rows at a time from its checkpoint.

namespace mostyle {
namespace {

using detail::check_series;
using detail::local_costs;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr unsigned kStart = 0, kDiagonal = 1;  // then (1, k): k; (k, 1): max_slope + k - 1
constexpr int kPairSamples = 64;
constexpr double kCoarseCells = 250000.0;  // cells of the automatic penalty's first pass, at most about

// The grid and its recurrence, row by row.
class Grid {
 public:
  Grid(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, int slope, bool open, double penalty, JobControl* control)
      : a_(a), b_(b), n_(static_cast<int>(a.rows())), m_(static_cast<int>(b.rows())), s_(slope), open_(open),
        penalty_(penalty), control_(control), d_((s_ + 1) * stride()), c_(s_ * stride(), kInf) {}

  int n() const { return n_; }
  int m() const { return m_; }
  int stride() const { return m_ + s_; }  // s_ columns of +inf padding on the left

  double* d_row(int i) { return d_.data() + static_cast<std::size_t>((i % (s_ + 1) + s_ + 1) % (s_ + 1)) * stride() + s_; }
  double* c_row(int i) { return c_.data() + static_cast<std::size_t>(i % s_) * stride() + s_; }

  // Fills row i's local costs (minus the penalty).
  void costs(int i) {
    double* c = c_row(i);
    local_costs(a_, i, b_, 0, m_, c);
    if (penalty_ != 0.0)
      for (int j = 0; j < m_; ++j) c[j] -= penalty_;
  }

  // Rows before 0 are +inf.
  void clear_row(int i) {
    double* d = d_row(i) - s_;
    std::fill(d, d + stride(), kInf);
  }

  // Row i of D from rows i-1 .. i-s (already in the ring) and c rows i-s+1 .. i; codes: m_
  // nibbles or nullptr.
  void relax(int i, std::uint8_t* codes) {
    check_cancel(control_);
    costs(i);
    double* d = d_row(i);
    std::fill(d - s_, d, kInf);
    const double* c = c_row(i);
    const double* up[5] = {nullptr, nullptr, nullptr, nullptr, nullptr};
    const double* cup[5] = {nullptr, nullptr, nullptr, nullptr, nullptr};
    for (int k = 1; k <= s_; ++k) {
      up[k] = i - k >= 0 ? d_row(i - k) : nullptr;
      cup[k] = i - k + 1 >= 0 ? c_row(i - k + 1) : nullptr;  // cup[1] == c
    }
    if (s_ == 2 && i >= 2 && open_) {  // the default, off the first rows: no branches on j
      relax_slope2(c, up[1], up[2], cup[2], d, codes);
      return;
    }
    for (int j = 0; j < m_; ++j) {
      double best = (open_ || (i == 0 && j == 0)) ? 2.0 * c[j] : kInf;
      unsigned code = kStart;
      if (up[1] != nullptr) {
        const double diagonal = up[1][j - 1] + 2.0 * c[j];  // padding makes j - 1 < 0 +inf
        if (diagonal < best || (diagonal == best && code == kStart)) {
          best = diagonal;
          code = kDiagonal;
        }
        double run_b = c[j], run_a = c[j];  // c of the cells a (1, k) / (k, 1) step passes after its first
        for (int k = 2; k <= s_; ++k) {
          if (j - k + 1 >= 0) {
            const double v = up[1][j - k] + 2.0 * c[j - k + 1] + run_b;
            if (v < best) {
              best = v;
              code = static_cast<unsigned>(k);
            }
            run_b += c[j - k + 1];
          }
          if (up[k] != nullptr) {
            const double v = up[k][j - 1] + 2.0 * cup[k][j] + run_a;
            if (v < best) {
              best = v;
              code = static_cast<unsigned>(s_ + k - 1);
            }
            run_a += cup[k][j];
          }
        }
      }
      d[j] = best;
      if (codes != nullptr) {
        std::uint8_t& byte = codes[j >> 1];
        byte = static_cast<std::uint8_t>((j & 1) ? (byte & 0x0f) | (code << 4) : (byte & 0xf0) | code);
      }
    }
  }

  // relax() for max_slope 2 and open ends: c and c1 are rows i and i-1 of local costs, d1 and
  // d2 rows i-1 and i-2 of D; the left padding (+inf in D, in c) stands in for j - 1, j - 2 < 0.
  void relax_slope2(const double* c, const double* d1, const double* d2, const double* c1, double* d,
                    std::uint8_t* codes) const {
    for (int j = 0; j < m_; ++j) {
      const double cj = c[j];
      double best = 2.0 * cj;
      unsigned code = kStart;
      const double diagonal = d1[j - 1] + 2.0 * cj;
      if (diagonal <= best) {
        best = diagonal;
        code = kDiagonal;
      }
      const double across = d1[j - 2] + 2.0 * c[j - 1] + cj;  // (1, 2)
      if (across < best) {
        best = across;
        code = 2;
      }
      const double down = d2[j - 1] + 2.0 * c1[j] + cj;  // (2, 1)
      if (down < best) {
        best = down;
        code = 3;
      }
      d[j] = best;
      if (codes != nullptr) {
        std::uint8_t& byte = codes[j >> 1];
        byte = static_cast<std::uint8_t>((j & 1) ? (byte & 0x0f) | (code << 4) : (byte & 0xf0) | code);
      }
    }
  }

  // The step a code stands for: (di, dj).
  std::pair<int, int> step(unsigned code) const {
    if (code == kDiagonal) return {1, 1};
    if (code <= static_cast<unsigned>(s_)) return {1, static_cast<int>(code)};
    return {static_cast<int>(code) - s_ + 1, 1};
  }

  // Local cost (penalty added back) of the cells a step into (i, j) passes, weighted.
  double step_cost(int i, int j, unsigned code) const {
    auto c = [&](int r, int col) {
      double v = 0.0;
      for (Eigen::Index k = 0; k < a_.cols(); ++k) v += (a_(r, k) - b_(col, k)) * (a_(r, k) - b_(col, k));
      return std::sqrt(v);
    };
    if (code == kStart) return 2.0 * c(i, j);
    const auto [di, dj] = step(code);
    double sum = 0.0;
    if (di == 1) {
      for (int t = j - dj + 1; t <= j; ++t) sum += (t == j - dj + 1 ? 2.0 : 1.0) * c(i, t);
    } else {
      for (int t = i - di + 1; t <= i; ++t) sum += (t == i - di + 1 ? 2.0 : 1.0) * c(t, j);
    }
    return sum;
  }

 private:
  const Eigen::MatrixXd& a_;
  const Eigen::MatrixXd& b_;
  int n_, m_, s_;
  bool open_;
  double penalty_;
  JobControl* control_;
  std::vector<double> d_, c_;
};

int covered_frames(const SlopeDtwPath& path) {
  return (path.steps.back().first - path.steps.front().first + 1) +
         (path.steps.back().second - path.steps.front().second + 1);
}

unsigned nibble(const std::vector<std::uint8_t>& codes, std::size_t row_bytes, int r, int j) {
  const std::uint8_t byte = codes[static_cast<std::size_t>(r) * row_bytes + (j >> 1)];
  return (j & 1) ? byte >> 4 : byte & 0x0fu;
}

}  // namespace

void SlopeDtwOptions::Validate() const {
  if (max_slope < 2 || max_slope > 4)
    throw InputError("expected a DTW slope limit from 2 to 4, found " + std::to_string(max_slope));
  if (!std::isfinite(end_penalty))
    throw InputError("expected a finite DTW end penalty (negative: automatic)");
}

double median_pair_cost(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  const int n = static_cast<int>(a.rows()), m = static_cast<int>(b.rows());
  const int rows = std::min(n, kPairSamples), cols = std::min(m, kPairSamples);
  std::vector<double> costs;
  costs.reserve(static_cast<std::size_t>(rows) * cols);
  for (int r = 0; r < rows; ++r) {
    const int i = static_cast<int>((r + 0.5) * n / rows);
    for (int q = 0; q < cols; ++q) {
      const int j = static_cast<int>((q + 0.5) * m / cols);
      costs.push_back((a.row(i) - b.row(j)).norm());
    }
  }
  auto mid = costs.begin() + static_cast<std::ptrdiff_t>(costs.size() / 2);
  std::nth_element(costs.begin(), mid, costs.end());
  return *mid;
}

namespace {

SlopeDtwPath solve(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const SlopeDtwOptions& o, double penalty,
                   JobControl* control);

}  // namespace

SlopeDtwPath align_slope_dtw(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const SlopeDtwOptions& o,
                             JobControl* control) {
  o.Validate();
  check_series(a, "a");
  check_series(b, "b");
  if (a.cols() != b.cols()) {
    std::ostringstream s;
    s << "DTW inputs have different feature counts: a has " << a.cols() << " columns, b has " << b.cols() << ".";
    throw InputError(s.str());
  }
  const int n = static_cast<int>(a.rows()), m = static_cast<int>(b.rows()), slope = o.max_slope;
  if (!o.open_ends && (std::max(n, m) - 1 > slope * (std::min(n, m) - 1))) {
    std::ostringstream s;
    s << "takes of " << n << " and " << m << " frames cannot be aligned end to end with neither running more than "
      << slope << " times faster than the other; use open ends";
    throw InputError(s.str());
  }
  if (!o.open_ends) return solve(a, b, o, 0.0, control);
  if (o.end_penalty >= 0) return solve(a, b, o, o.end_penalty, control);
  // Automatic: a generous first pass finds the part that matches; frames at the ends that match
  // kEndPenaltyOfPath times worse than that part does are then left out (within the bounds).
  // The first pass only estimates the cost per matched frame: on long takes it runs on every
  // q-th frame of both (about kCoarseCells cells), the second at full resolution.
  const double random = median_pair_cost(a, b);
  const double cells = static_cast<double>(a.rows()) * static_cast<double>(b.rows());
  const int q = std::max(1, static_cast<int>(std::floor(std::sqrt(cells / kCoarseCells))));
  auto every = [q](const Eigen::MatrixXd& x) {
    Eigen::MatrixXd out((x.rows() + q - 1) / q, x.cols());
    for (Eigen::Index r = 0; r < out.rows(); ++r) out.row(r) = x.row(r * q);
    return out;
  };
  const SlopeDtwPath first =
      q == 1 ? solve(a, b, o, kEndPenaltyMax * random, control) : solve(every(a), every(b), o, kEndPenaltyMax * random, control);
  const double per_frame = first.cost / std::max(1, covered_frames(first));
  const double penalty = std::clamp(kEndPenaltyOfPath * per_frame, kEndPenaltyMin * random, kEndPenaltyMax * random);
  if (q == 1 && penalty == first.end_penalty) return first;
  return solve(a, b, o, penalty, control);
}

namespace {

SlopeDtwPath solve(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const SlopeDtwOptions& o, double penalty,
                   JobControl* control) {
  const int n = static_cast<int>(a.rows()), m = static_cast<int>(b.rows()), slope = o.max_slope;
  Grid grid(a, b, slope, o.open_ends, penalty, control);
  const std::size_t row_bytes = (static_cast<std::size_t>(m) + 1) / 2;
  // Rows per segment: all of them when their pointers fit the budget.
  const std::size_t budget_rows = std::max<std::size_t>(1, o.pointer_budget_bytes / row_bytes);
  const int segment = budget_rows >= static_cast<std::size_t>(n) ? n : std::max<int>(slope, static_cast<int>(budget_rows));
  const bool one_pass = segment >= n;

  std::vector<std::uint8_t> codes(static_cast<std::size_t>(segment) * row_bytes, 0);
  std::vector<double> checkpoints;  // per segment after the first: rows r0 - slope .. r0 - 1, m each
  double best = kInf;
  int end_i = -1, end_j = -1;
  for (int k = 1; k <= slope; ++k) grid.clear_row(-k);
  for (int i = 0; i < n; ++i) {
    if (!one_pass && i % segment == 0 && i > 0)
      for (int r = i - slope; r < i; ++r) {
        const double* d = grid.d_row(r);
        checkpoints.insert(checkpoints.end(), d, d + m);
      }
    grid.relax(i, one_pass ? codes.data() + static_cast<std::size_t>(i) * row_bytes : nullptr);
    const double* d = grid.d_row(i);
    if (o.open_ends) {
      for (int j = 0; j < m; ++j)
        if (d[j] < best) {
          best = d[j];
          end_i = i;
          end_j = j;
        }
    } else if (i == n - 1) {
      best = d[m - 1];
      end_i = n - 1;
      end_j = m - 1;
    }
    report_progress(control, static_cast<float>(one_pass ? 0.9 * (i + 1) / n : 0.45 * (i + 1) / n));
  }
  if (!std::isfinite(best)) {
    std::ostringstream s;
    s << "DTW cost overflowed to infinity: the feature values (largest magnitude "
      << std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff()) << ") are too large; scale them down.";
    throw InputError(s.str());
  }

  // Traceback, one segment at a time (recomputed from its checkpoint unless one pass kept all).
  SlopeDtwPath path;
  path.end_penalty = penalty;
  int i = end_i, j = end_j, loaded = one_pass ? 0 : -1;
  while (true) {
    const int seg = i / segment;
    if (!one_pass && seg != loaded) {
      const int r0 = seg * segment, r1 = std::min(n, r0 + segment);
      for (int k = 1; k <= slope; ++k) grid.clear_row(r0 - k);
      if (seg > 0) {
        const double* saved = checkpoints.data() + static_cast<std::size_t>(seg - 1) * slope * m;
        for (int k = 0; k < slope; ++k) std::copy(saved + k * m, saved + (k + 1) * m, grid.d_row(r0 - slope + k));
        for (int r = std::max(0, r0 - slope + 1); r < r0; ++r) grid.costs(r);
      }
      for (int r = r0; r < r1 && r <= i; ++r)
        grid.relax(r, codes.data() + static_cast<std::size_t>(r - r0) * row_bytes);
      loaded = seg;
    }
    path.steps.emplace_back(i, j);
    const unsigned code = nibble(codes, row_bytes, i - seg * segment, j);
    path.cost += grid.step_cost(i, j, code);
    if (code == kStart) break;
    const auto [di, dj] = grid.step(code);
    i -= di;
    j -= dj;
  }
  std::reverse(path.steps.begin(), path.steps.end());
  path.objective = path.cost + penalty * (n + m - covered_frames(path));
  report_progress(control, 1.0f);
  return path;
}

}  // namespace

}  // namespace mostyle
