#include "engine/align/cycles.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "engine/io/error.h"

namespace mostyle {
namespace {

constexpr int kPeriodicChannels = 6;    // the channels that move most carry the period
constexpr double kHarmonicShare = 0.85;  // a peak at P/d this high is the period instead of P
constexpr double kBoundarySlack = 0.3;   // a period boundary is looked for within +-30% of P
constexpr double kMinCycleAmplitude = 0.5;  // of the median cycle's: less is a still stretch

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  return v[mid];
}

// Cycles from one foot's strikes to its next, with a strike of the other foot in between, of a
// plausible length and not far from the take's median cycle.
std::vector<Cycle> gait_cycles(const Eigen::MatrixXd& contacts, int foot, double fps, const CycleOptions& o) {
  // A foot lands once per cycle: landing again sooner than the shortest cycle is not a step (the
  // contact flickered, or the foot shuffles in place), and that strike is passed over.
  auto debounced = [&](std::vector<int> strikes) {
    std::vector<int> kept;
    for (int f : strikes)
      if (kept.empty() || f - kept.back() >= o.min_gait_s * fps) kept.push_back(f);
    return kept;
  };
  const std::vector<int> own = debounced(foot_strikes(contacts, foot));
  const std::vector<int> other = debounced(foot_strikes(contacts, 1 - foot));
  const double shortest = o.min_gait_s * fps, longest = o.max_gait_s * fps;
  std::vector<Cycle> candidates;
  for (size_t k = 0; k + 1 < own.size(); ++k) {
    const int s = own[k], e = own[k + 1];
    if (e - s < shortest || e - s > longest) continue;
    const auto step = std::upper_bound(other.begin(), other.end(), s);
    if (step == other.end() || *step >= e) continue;  // the other foot did not step in between
    candidates.push_back({s, e});
  }
  std::vector<double> lengths;
  for (const Cycle& c : candidates) lengths.push_back(c.frames());
  const double typical = median(lengths);
  std::vector<Cycle> out;
  for (const Cycle& c : candidates)
    if (std::abs(c.frames() - typical) <= o.max_change * typical) out.push_back(c);
  return out;
}

// Periods of the channels that move most (autocorrelation), cut at the minima of the one that
// moves most.
TakeCycles periodic_cycles(const Eigen::MatrixXd& local, double fps, double leg_length, const CycleOptions& o) {
  TakeCycles none;
  const Eigen::Index frames = local.rows();
  if (frames < 4) return none;
  const Eigen::MatrixXd centred = local.rowwise() - local.colwise().mean();
  const Eigen::RowVectorXd spread = (centred.colwise().squaredNorm() / double(frames)).cwiseSqrt();
  std::vector<Eigen::Index> moving;
  for (Eigen::Index c = 0; c < spread.size(); ++c)
    if (spread[c] >= o.min_amplitude * leg_length) moving.push_back(c);
  if (moving.empty()) return none;  // standing still
  std::sort(moving.begin(), moving.end(), [&](Eigen::Index a, Eigen::Index b) { return spread[a] > spread[b]; });
  moving.resize(std::min<size_t>(moving.size(), kPeriodicChannels));
  Eigen::MatrixXd x(frames, static_cast<Eigen::Index>(moving.size()));
  for (size_t k = 0; k < moving.size(); ++k)
    x.col(static_cast<Eigen::Index>(k)) = centred.col(moving[k]) / spread[moving[k]];

  const int min_lag = std::max(2, static_cast<int>(std::lround(o.min_period_s * fps)));
  const int max_lag = std::min(static_cast<int>(std::lround(o.max_period_s * fps)), static_cast<int>(frames / 2));
  if (max_lag <= min_lag + 1) return none;  // too short to repeat
  std::vector<double> r(static_cast<size_t>(max_lag + 2), 0.0);
  for (int lag = min_lag - 1; lag <= max_lag + 1 && lag < frames; ++lag) {
    const Eigen::Index n = frames - lag;
    r[static_cast<size_t>(lag)] =
        (x.topRows(n).array() * x.bottomRows(n).array()).sum() / (double(n) * double(x.cols()));
  }
  auto peak = [&](int lag) {
    return lag > min_lag - 1 && lag < max_lag + 1 && r[static_cast<size_t>(lag)] >= r[static_cast<size_t>(lag - 1)] &&
           r[static_cast<size_t>(lag)] >= r[static_cast<size_t>(lag + 1)];
  };
  int best = -1;
  for (int lag = min_lag; lag <= max_lag; ++lag)
    if (peak(lag) && (best < 0 || r[static_cast<size_t>(lag)] > r[static_cast<size_t>(best)])) best = lag;
  if (best < 0 || r[static_cast<size_t>(best)] < o.min_periodicity) return none;
  // A multiple of the period can correlate as well as the period itself: take the shortest.
  for (int d = 4; d >= 2; --d) {
    const int guess = static_cast<int>(std::lround(double(best) / d));
    const int slack = std::max(1, static_cast<int>(0.15 * guess));
    int found = -1;
    for (int lag = std::max(min_lag, guess - slack); lag <= std::min(max_lag, guess + slack); ++lag)
      if (peak(lag) && r[static_cast<size_t>(lag)] >= kHarmonicShare * r[static_cast<size_t>(best)] &&
          (found < 0 || r[static_cast<size_t>(lag)] > r[static_cast<size_t>(found)]))
        found = lag;
    if (found >= 0) {
      best = found;
      break;
    }
  }

  // Boundaries at the minima of the channel that moves most, one period apart (within slack).
  const double period = best;
  const auto anchor = x.col(0);
  auto lowest = [&](Eigen::Index from, Eigen::Index to) {  // [from, to]
    Eigen::Index at = from;
    for (Eigen::Index f = from + 1; f <= to; ++f)
      if (anchor[f] < anchor[at]) at = f;
    return at;
  };
  std::vector<Cycle> cycles;
  Eigen::Index begin = lowest(0, std::min<Eigen::Index>(frames - 1, best - 1));
  for (;;) {
    const Eigen::Index from = begin + static_cast<Eigen::Index>(std::lround((1.0 - kBoundarySlack) * period));
    const Eigen::Index to =
        std::min<Eigen::Index>(frames - 1, begin + static_cast<Eigen::Index>(std::lround((1.0 + kBoundarySlack) * period)));
    if (from > to) break;
    const Eigen::Index end = lowest(from, to);
    if (end == frames - 1 && end < begin + (1.0 + kBoundarySlack) * period) break;  // cut off by the take's end
    cycles.push_back({static_cast<int>(begin), static_cast<int>(end)});
    begin = end;
  }
  // Cycles where the joints hardly move, in either half (a still start or end), are not cycles of
  // the action.
  auto range = [&](Eigen::Index from, Eigen::Index to) {  // [from, to]
    const auto rows = x.middleRows(from, to - from + 1);
    return (rows.colwise().maxCoeff() - rows.colwise().minCoeff()).sum();
  };
  std::vector<double> amplitude, first_half, second_half;
  for (const Cycle& c : cycles) {
    const int middle = (c.begin + c.end) / 2;
    amplitude.push_back(range(c.begin, c.end));
    first_half.push_back(range(c.begin, middle));
    second_half.push_back(range(middle, c.end));
  }
  const double typical = median(amplitude);
  TakeCycles out;
  for (size_t k = 0; k < cycles.size(); ++k)
    if (amplitude[k] >= kMinCycleAmplitude * typical && first_half[k] >= 0.5 * kMinCycleAmplitude * typical &&
        second_half[k] >= 0.5 * kMinCycleAmplitude * typical)
      out.cycles.push_back(cycles[k]);
  if (out.cycles.empty()) return none;
  out.kind = CycleKind::kPeriodic;
  out.period = period;
  return out;
}

}  // namespace

const char* cycle_kind_name(CycleKind kind) {
  switch (kind) {
    case CycleKind::kGait:
      return "gait";
    case CycleKind::kPeriodic:
      return "periodic";
    case CycleKind::kNone:
      break;
  }
  return "none";
}

void CycleOptions::Validate() const {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(min_gait_s) || !positive(max_gait_s) || !(min_gait_s < max_gait_s))
    throw InputError("cycle detection: a gait cycle's shortest and longest length must be positive, shortest first");
  if (!positive(min_period_s) || !positive(max_period_s) || !(min_period_s < max_period_s))
    throw InputError("cycle detection: a period's shortest and longest length must be positive, shortest first");
  if (!(max_change > 0.0 && max_change < 1.0))
    throw InputError("cycle detection: the change allowed from the typical cycle must be above 0 and below 1");
  if (!(min_periodicity > 0.0 && min_periodicity <= 1.0))
    throw InputError("cycle detection: the periodicity asked for must be above 0, up to 1");
  if (!(min_amplitude >= 0.0) || !std::isfinite(min_amplitude))
    throw InputError("cycle detection: the smallest amplitude must be a number from 0 up");
  if (foot < -1 || foot > 1) throw InputError("cycle detection: the foot must be left (0), right (1) or either (-1)");
}

int TakeCycles::frames_in_cycles() const {
  int n = 0;
  for (const Cycle& c : cycles) n += c.frames();
  return n;
}

std::vector<int> foot_strikes(const Eigen::MatrixXd& contacts, int foot) {
  std::vector<int> out;
  for (Eigen::Index t = 1; t < contacts.rows(); ++t)
    if (contacts(t, foot) > 0.5 && contacts(t - 1, foot) <= 0.5) out.push_back(static_cast<int>(t));
  return out;
}

std::vector<int> cycle_starts_at(const TakeCycles& cycles, const Eigen::VectorXd& frames) {
  std::vector<int> out;
  const std::vector<Cycle>& c = cycles.cycles;  // in order: their begins ascend
  for (Eigen::Index k = 0; k < frames.size(); ++k) {
    if (k == 0) {
      const auto at = std::lower_bound(c.begin(), c.end(), frames[0],
                                       [](const Cycle& cycle, double f) { return cycle.begin < f; });
      if (at != c.end() && at->begin == frames[0]) out.push_back(0);
      continue;
    }
    // The first begin above frames[k - 1]: reached when frames[k] is at or past it.
    const auto at = std::upper_bound(c.begin(), c.end(), frames[k - 1],
                                     [](double f, const Cycle& cycle) { return f < cycle.begin; });
    if (at != c.end() && frames[k] >= at->begin) out.push_back(static_cast<int>(k));
  }
  return out;
}

TakeCycles detect_cycles(const Eigen::MatrixXd& contacts, const Eigen::MatrixXd& local, double fps, double leg_length,
                         const CycleOptions& options) {
  options.Validate();
  if (contacts.cols() != 2 || contacts.rows() != local.rows())
    throw InputError("cycle detection: expected two feet's contacts for each of the take's " +
                     std::to_string(local.rows()) + " frames, found " + std::to_string(contacts.rows()) + " x " +
                     std::to_string(contacts.cols()));
  if (!(fps > 0.0) || !(leg_length > 0.0))
    throw InputError("cycle detection: the frame rate and the leg length must be above 0");
  TakeCycles out;
  for (int foot : {0, 1}) {
    if (options.foot >= 0 && foot != options.foot) continue;
    std::vector<Cycle> cycles = gait_cycles(contacts, foot, fps, options);
    if (cycles.size() > out.cycles.size()) {
      out.cycles = std::move(cycles);
      out.foot = foot;
    }
  }
  if (!out.cycles.empty()) {
    out.kind = CycleKind::kGait;
    std::vector<double> lengths;
    for (const Cycle& c : out.cycles) lengths.push_back(c.frames());
    out.period = median(lengths);
    return out;
  }
  return periodic_cycles(local, fps, leg_length, options);
}

}  // namespace mostyle
