#include "engine/align/dtw.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>

#include "engine/base/error.h"

// DTW as the paper's section 3.2 uses it, with the recurrence, path and band of dtw.h. The cost runs row by row in O(m) memory. The path keeps 2-bit back-pointers for
// the cells in the band while they fit a byte budget; beyond it, Hirschberg's divide and conquer
// (costs forward to a middle row, backward from the end, best crossing, recurse) keeps memory
// linear for takes of any length at about twice the time.

namespace mostyle {
namespace detail {

void check_series(const Eigen::MatrixXd& x, const char* name) {
  if (x.rows() == 0 || x.cols() == 0) {
    std::ostringstream s;
    s << "DTW input " << name << " is empty (" << x.rows() << " frames x " << x.cols()
      << " features); both series need at least one frame and one feature.";
    throw InputError(s.str());
  }
  if (x.rows() >= std::numeric_limits<int>::max()) {
    std::ostringstream s;
    s << "DTW input " << name << " has " << x.rows() << " frames, more than DTW can index.";
    throw InputError(s.str());
  }
  for (Eigen::Index k = 0; k < x.cols(); ++k)
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      if (!std::isfinite(x(i, k))) {
        std::ostringstream s;
        s << "DTW input " << name << " has a non-finite value (" << x(i, k) << ") at frame " << i
          << ", feature " << k << ".";
        throw InputError(s.str());
      }
}

// Local costs of frame i of a against frames [j, j + len) of b, into c[0, len). Eigen's array
// expressions vectorise this part; the sum runs over features in order, as a scalar loop would.
void local_costs(const Eigen::MatrixXd& a, int i, const Eigen::MatrixXd& b, int j, int len,
                 double* c) {
  Eigen::Map<Eigen::ArrayXd> out(c, len);
  const auto diff = [&](Eigen::Index k) { return b.col(k).segment(j, len).array() - a(i, k); };
  switch (b.cols()) {
    case 1:
      out = diff(0).square().sqrt();
      break;
    case 2:
      out = (diff(0).square() + diff(1).square()).sqrt();
      break;
    case 3:
      out = (diff(0).square() + diff(1).square() + diff(2).square()).sqrt();
      break;
    default:
      out = diff(0).square();
      for (Eigen::Index k = 1; k < b.cols(); ++k) out += diff(k).square();
      out = out.sqrt();
  }
}

}  // namespace detail

using detail::check_series;
using detail::local_costs;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Back-pointer codes, four to a byte, the first cell of a group in the low bits.
constexpr unsigned kFromDiagonal = 0;  // (i-1, j-1)
constexpr unsigned kFromUp = 1;        // (i-1, j)
constexpr unsigned kFromLeft = 2;      // (i, j-1)

std::int64_t floor_div(std::int64_t num, std::int64_t den) {  // den > 0
  return num >= 0 ? num / den : -((-num + den - 1) / den);
}
std::int64_t ceil_div(std::int64_t num, std::int64_t den) { return -floor_div(-num, den); }

// The allowed columns [lo[i], hi[i]] of every row i of the full n x m grid. Both bounds are
// non-decreasing in i, which the row recurrence below relies on.
struct Band {
  std::vector<int> lo, hi;
};

// Cell (i, j) is in a band of half-width r when |j - i*(m-1)/(n-1)| <= r, evaluated exactly in
// integers as |j*(n-1) - i*(m-1)| <= r*(n-1). For n == 1 the scaled diagonal is the whole row.
Band make_band(int n, int m, int band) {
  Band out;
  out.lo.assign(n, 0);
  out.hi.assign(n, m - 1);
  if (band < 0 || n == 1) return out;
  const std::int64_t den = n - 1;
  for (int i = 0; i < n; ++i) {
    const std::int64_t centre = std::int64_t{i} * (m - 1);
    const std::int64_t lo = ceil_div(centre - std::int64_t{band} * den, den);
    const std::int64_t hi = floor_div(centre + std::int64_t{band} * den, den);
    out.lo[i] = static_cast<int>(std::max<std::int64_t>(lo, 0));
    out.hi[i] = static_cast<int>(std::min<std::int64_t>(hi, m - 1));
  }
  return out;
}

// A monotone path needs every row non-empty and each row to start no later than one column
// after the previous row ends; the corners are always inside a band.
bool band_connects(const Band& band) {
  const int n = static_cast<int>(band.lo.size());
  for (int i = 0; i < n; ++i) {
    if (band.lo[i] > band.hi[i]) return false;
    if (i > 0 && band.lo[i] > band.hi[i - 1] + 1) return false;
  }
  return true;
}

int least_connecting_band(int n, int m) {
  int lo = 0, hi = std::max(n, m);  // a band of max(n, m) holds every cell
  while (lo < hi) {
    const int mid = lo + (hi - lo) / 2;
    if (band_connects(make_band(n, m, mid)))
      hi = mid;
    else
      lo = mid + 1;
  }
  return lo;
}

Band checked_band(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const DtwOptions& o) {
  check_series(a, "a");
  check_series(b, "b");
  if (a.cols() != b.cols()) {
    std::ostringstream s;
    s << "DTW inputs have different feature counts: a has " << a.cols() << " columns, b has "
      << b.cols() << ".";
    throw InputError(s.str());
  }
  if (o.band < -1) {
    std::ostringstream s;
    s << "DTW band must be -1 (no band) or a half-width of at least 0 frames, not " << o.band
      << ".";
    throw InputError(s.str());
  }
  const int n = static_cast<int>(a.rows()), m = static_cast<int>(b.rows());
  Band band = make_band(n, m, o.band);
  if (!band_connects(band)) {
    std::ostringstream s;
    s << "DTW band of " << o.band << " frames is too narrow to connect frames (0, 0) to ("
      << n - 1 << ", " << m - 1 << ") of series with " << n << " and " << m
      << " frames; it needs at least " << least_connecting_band(n, m) << ".";
    throw InputError(s.str());
  }
  return band;
}

[[noreturn]] void throw_overflow(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  std::ostringstream s;
  s << "DTW cost overflowed to infinity: the feature values (largest magnitude "
    << std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff())
    << ") are too large; scale them down.";
  throw InputError(s.str());
}

// The grid as one direction sees it: either the inputs, or both reversed (row i is input row
// n-1-i) so the backward costs of divide and conquer reuse the forward code.
struct View {
  const Eigen::MatrixXd& a;
  const Eigen::MatrixXd& b;
  const Band& band;  // in input coordinates
  bool reversed;

  // Row i's allowed columns inside the rectangle's columns [j0, j1].
  void range(int i, int j0, int j1, int* lo, int* hi) const {
    const int n = static_cast<int>(band.lo.size()), m = static_cast<int>(b.rows());
    if (reversed) {
      *lo = std::max(j0, m - 1 - band.hi[n - 1 - i]);
      *hi = std::min(j1, m - 1 - band.lo[n - 1 - i]);
    } else {
      *lo = std::max(j0, band.lo[i]);
      *hi = std::min(j1, band.hi[i]);
    }
  }
};

struct Progress {
  JobControl* control = nullptr;
  double done = 0.0;
  double total = 1.0;  // cells the whole job is expected to visit

  void add_row(int cells) {
    check_cancel(control);
    done += cells;
    report_progress(control, static_cast<float>(std::min(1.0, done / total)));
  }
};

double local_cost(const Eigen::MatrixXd& a, int i, const Eigen::MatrixXd& b, int j) {
  double sum = 0.0;
  for (Eigen::Index k = 0; k < a.cols(); ++k) {
    const double d = b(j, k) - a(i, k);
    sum += d * d;
  }
  return std::sqrt(sum);
}

// One row of the recurrence over len cells. prev and cur point at the row's first column;
// prev[-1 .. len-1] hold the previous row (+inf outside its range), cur[-1] is +inf. The only
// serial dependency is cur[k-1] -> cur[k] through one min and one add; everything else is off
// that chain, so the loop runs at about the latency of those two instructions.
void relax_row(const double* c, const double* prev, double* cur, int len) {
  double left = cur[-1];
  for (int k = 0; k < len; ++k) {
    left = c[k] + std::min(std::min(prev[k - 1], prev[k]), left);
    cur[k] = left;
  }
}

// The same, also writing each cell's back-pointer into codes[0, (len+3)/4). The choice matches
// the value exactly (std::min keeps its first argument on ties), so a traceback's summed local
// costs reproduce D bit for bit.
void relax_row_with_codes(const double* c, const double* prev, double* cur, int len,
                          std::uint8_t* codes) {
  double left = cur[-1];
  unsigned byte = 0;
  for (int k = 0; k < len; ++k) {
    const double diagonal = prev[k - 1], up = prev[k];
    const double vertical = std::min(diagonal, up);
    const bool from_left = left < vertical;
    const unsigned code = from_left ? kFromLeft : (up < diagonal ? kFromUp : kFromDiagonal);
    left = c[k] + (from_left ? left : vertical);
    cur[k] = left;
    byte |= code << (2 * (k & 3));
    if ((k & 3) == 3) {
      codes[k >> 2] = static_cast<std::uint8_t>(byte);
      byte = 0;
    }
  }
  if (len & 3) codes[len >> 2] = static_cast<std::uint8_t>(byte);
}

// Back-pointers of the rows of one rectangle, each row's cells from its first allowed column.
struct Pointers {
  std::vector<std::int64_t> row_offset;  // byte where row i0 + r starts
  std::vector<int> row_lo;               // first column of row i0 + r
  std::vector<std::uint8_t> bytes;

  unsigned code(int r, int j) const {
    const std::int64_t k = j - row_lo[r];
    return (bytes[row_offset[r] + (k >> 2)] >> (2 * (k & 3))) & 3u;
  }
};

// Bytes the back-pointers of rows i0..i1, columns j0..j1 of v would take.
std::size_t pointer_bytes(const View& v, int i0, int i1, int j0, int j1) {
  std::size_t bytes = 0;
  for (int i = i0; i <= i1; ++i) {
    int lo, hi;
    v.range(i, j0, j1, &lo, &hi);
    bytes += static_cast<std::size_t>(hi - lo + 1 + 3) / 4 + sizeof(std::int64_t) + sizeof(int);
  }
  return bytes;
}

// Runs the recurrence on v from the cell (i0, j0) over rows i0..i_last within columns j0..j1 and
// returns row i_last: element j - j0 + 1 holds D(i_last, j), +inf outside the row's range
// (element 0 stands for column j0 - 1). With `pointers`, also records every row's back-pointers.
std::vector<double> run_rows(const View& v, int i0, int i_last, int j0, int j1,
                             Pointers* pointers, Progress& progress) {
  const int width = j1 - j0 + 1;
  std::vector<double> prev(width + 1, kInf), cur(width + 1, kInf), c(width);
  // A virtual row above i0 whose one finite cell, at column j0 - 1, feeds (i0, j0) diagonally
  // with 0, so the first row needs no special case.
  prev[0] = 0.0;
  int prev_lo = j0 - 1;
  [[maybe_unused]] int prev_hi = j0 - 1;  // for the assertion only
  for (int i = i0; i <= i_last; ++i) {
    int lo, hi;
    v.range(i, j0, j1, &lo, &hi);
    // Both ends of the ranges only move right, so the previous row's buffer is still +inf
    // after its range (never written there) and holds its row or +inf from lo - 1 on.
    assert(lo <= hi && lo <= prev_hi + 1 && hi >= prev_hi && lo >= prev_lo);
    cur[lo - j0] = kInf;  // column lo - 1: no left neighbour, and +inf for the next row
    const int len = hi - lo + 1;
    local_costs(v.a, i, v.b, lo, len, c.data());
    if (pointers) {
      const int r = i - i0;
      relax_row_with_codes(c.data(), &prev[lo - j0 + 1], &cur[lo - j0 + 1], len,
                           &pointers->bytes[pointers->row_offset[r]]);
    } else {
      relax_row(c.data(), &prev[lo - j0 + 1], &cur[lo - j0 + 1], len);
    }
    if (i == i0) prev[0] = kInf;  // retire the virtual row
    std::swap(prev, cur);
    prev_lo = lo;
    prev_hi = hi;
    progress.add_row(len);
  }
  // Rows read nothing before column lo - 1, so stale values may sit there; clear them.
  std::fill(prev.begin(), prev.begin() + (prev_lo - j0 + 1), kInf);
  return prev;
}

// The optimal path of the rectangle from (i0, j0) to (i1, j1) through stored back-pointers,
// appended to `steps`. Returns its cost D(i1, j1).
double solve_with_pointers(const View& v, int i0, int i1, int j0, int j1, Progress& progress,
                           std::vector<std::pair<int, int>>& steps) {
  Pointers p;
  const int rows = i1 - i0 + 1;
  p.row_offset.resize(rows);
  p.row_lo.resize(rows);
  std::int64_t bytes = 0;
  for (int r = 0; r < rows; ++r) {
    int lo, hi;
    v.range(i0 + r, j0, j1, &lo, &hi);
    p.row_offset[r] = bytes;
    p.row_lo[r] = lo;
    bytes += (hi - lo + 1 + 3) / 4;
  }
  p.bytes.resize(static_cast<std::size_t>(bytes));
  const std::vector<double> last = run_rows(v, i0, i1, j0, j1, &p, progress);
  const double cost = last[j1 - j0 + 1];
  if (!std::isfinite(cost)) throw_overflow(v.a, v.b);

  const std::size_t first = steps.size();
  int i = i1, j = j1;
  steps.emplace_back(i, j);
  while (i != i0 || j != j0) {
    const unsigned code = p.code(i - i0, j);
    if (code != kFromLeft) --i;
    if (code != kFromUp) --j;
    assert(i >= i0 && j >= j0);
    steps.emplace_back(i, j);
  }
  std::reverse(steps.begin() + static_cast<std::ptrdiff_t>(first), steps.end());
  return cost;
}

// Hirschberg's split for the DTW recurrence: with forward costs F of row mid and backward costs
// G of row mid + 1 (G(i, j) = the best cost from (i, j) to (i1, j1), both ends included), a path
// leaves row mid at its last cell (mid, j) and steps to (mid+1, j) or (mid+1, j+1), so the
// optimum is min over j of F(mid, j) + min(G(mid+1, j), G(mid+1, j+1)).
void split(const View& forward, const View& backward, int i0, int i1, int j0, int j1, int mid,
           Progress& progress, int* j_leave, int* j_enter) {
  const int n = static_cast<int>(forward.a.rows()), m = static_cast<int>(forward.b.rows());
  const std::vector<double> f = run_rows(forward, i0, mid, j0, j1, nullptr, progress);
  // Backward: the reversed grid from (n-1-i1, m-1-j1) down to its row n-1-(mid+1); its element
  // jr - (m-1-j1) + 1 with jr = m-1-j is j1 - j + 1.
  const std::vector<double> g =
      run_rows(backward, n - 1 - i1, n - 1 - (mid + 1), m - 1 - j1, m - 1 - j0, nullptr, progress);
  double best = kInf;
  *j_leave = -1;
  for (int j = j0; j <= j1; ++j) {
    const double fj = f[j - j0 + 1];
    if (fj == kInf) continue;
    const double down = g[j1 - j + 1];
    const double diagonal = j < j1 ? g[j1 - j] : kInf;
    const double total = fj + std::min(down, diagonal);
    if (total < best) {
      best = total;
      *j_leave = j;
      *j_enter = diagonal < down ? j + 1 : j;
    }
  }
  if (!(best < kInf)) throw_overflow(forward.a, forward.b);
}

void solve(const View& forward, const View& backward, int i0, int i1, int j0, int j1,
           std::size_t budget, Progress& progress, std::vector<std::pair<int, int>>& steps) {
  if (i0 == i1) {  // one row: the only path runs along it
    for (int j = j0; j <= j1; ++j) steps.emplace_back(i0, j);
    return;
  }
  if (j0 == j1) {  // one column: straight down
    for (int i = i0; i <= i1; ++i) steps.emplace_back(i, j0);
    return;
  }
  if (pointer_bytes(forward, i0, i1, j0, j1) <= budget) {
    solve_with_pointers(forward, i0, i1, j0, j1, progress, steps);
    return;
  }
  const int mid = i0 + (i1 - i0) / 2;
  int j_leave = 0, j_enter = 0;
  split(forward, backward, i0, i1, j0, j1, mid, progress, &j_leave, &j_enter);
  solve(forward, backward, i0, mid, j0, j_leave, budget, progress, steps);
  solve(forward, backward, mid + 1, i1, j_enter, j1, budget, progress, steps);
}

std::int64_t band_cells(const Band& band) {
  std::int64_t cells = 0;
  for (std::size_t i = 0; i < band.lo.size(); ++i) cells += band.hi[i] - band.lo[i] + 1;
  return cells;
}

}  // namespace

DtwPath align_dtw(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const DtwOptions& o,
                  JobControl* control) {
  const Band band = checked_band(a, b, o);
  const int n = static_cast<int>(a.rows()), m = static_cast<int>(b.rows());
  const View forward{a, b, band, false};
  Progress progress;
  progress.control = control;
  progress.total = static_cast<double>(band_cells(band));

  DtwPath path;
  path.steps.reserve(static_cast<std::size_t>(n) + m - 1);
  if (pointer_bytes(forward, 0, n - 1, 0, m - 1) <= o.pointer_budget_bytes) {
    path.cost = solve_with_pointers(forward, 0, n - 1, 0, m - 1, progress, path.steps);
  } else {
    // Each level of the recursion visits about half the cells of the one above.
    progress.total *= 2.0;
    const Eigen::MatrixXd a_reversed = a.colwise().reverse();
    const Eigen::MatrixXd b_reversed = b.colwise().reverse();
    const View backward{a_reversed, b_reversed, band, true};
    solve(forward, backward, 0, n - 1, 0, m - 1, o.pointer_budget_bytes, progress, path.steps);
    // Summed from the start, in the order the forward recurrence adds them.
    double cost = 0.0;
    for (const auto& [i, j] : path.steps) cost = local_cost(a, i, b, j) + cost;
    if (!std::isfinite(cost)) throw_overflow(a, b);
    path.cost = cost;
  }
  report_progress(control, 1.0f);
  return path;
}

Eigen::VectorXd warp_map(const DtwPath& path, int n) {
  if (n < 1) {
    std::ostringstream s;
    s << "A DTW warp needs at least one frame to warp onto, not " << n << ".";
    throw InputError(s.str());
  }
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(n);
  std::vector<int> count(n, 0);
  for (const auto& [i, j] : path.steps) {
    if (i < 0 || i >= n || j < 0) {
      std::ostringstream s;
      s << "DTW path step (" << i << ", " << j << ") lies outside frames 0.." << n - 1
        << " of the series it should warp onto.";
      throw InputError(s.str());
    }
    sum[i] += j;
    ++count[i];
  }
  for (int i = 0; i < n; ++i) {
    if (count[i] == 0) {
      std::ostringstream s;
      s << "DTW path matches nothing to frame " << i << " of the " << n
        << " frames it should warp onto.";
      throw InputError(s.str());
    }
    sum[i] /= count[i];
  }
  return sum;
}

}  // namespace mostyle
