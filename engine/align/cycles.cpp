#include "engine/align/cycles.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <string>

#include "engine/align/loop_clip.h"
#include "engine/base/error.h"
#include "engine/measure/foot_contact.h"

namespace mostyle {
namespace {

constexpr int kPeriodicChannels = 6;    // the channels that move most carry the period
constexpr double kBoundarySlack = 0.3;   // a period boundary is looked for within +-30% of P
constexpr double kMinCycleAmplitude = 0.5;  // of the median cycle's: less is a still stretch

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  return v[mid];
}

// How far a foot's cycles got through the checks, in order; the furthest tells why there are none.
enum class GaitStage { kNoStrike, kOneStrike, kLength, kNoStep, kTogether, kUneven, kPosture, kStride, kCycles };

const char* foot_name(int foot) { return foot == 0 ? "left" : "right"; }

// Why a foot gives no gait cycles, having got as far as `stage`.
std::string gait_reason(GaitStage stage, int foot, const CycleOptions& o) {
  const std::string own = foot_name(foot), other = foot_name(1 - foot);
  char range[64];
  switch (stage) {
    case GaitStage::kNoStrike:
      return "no foot strike of the " + own + " foot";
    case GaitStage::kOneStrike:
      return "the " + own + " foot strikes only once";
    case GaitStage::kLength:
      std::snprintf(range, sizeof range, "%.1f to %.1f s", o.min_gait_s, o.max_gait_s);
      return "the " + own + " foot's strikes are not a gait cycle (" + range + ") apart";
    case GaitStage::kNoStep:
      return "the " + other + " foot does not step between the " + own + " foot's strikes";
    case GaitStage::kTogether:
      return "the feet land together (a jump)";
    case GaitStage::kUneven:
      return "the feet do not take turns: the " + other + " foot lands twice between the " + own + " foot's strikes";
    case GaitStage::kPosture:
      return "the hips are low (not walking or running)";
    case GaitStage::kStride:
      return "the feet do not step: they move little against the body";
    case GaitStage::kCycles:
      break;
  }
  return "";
}

// Frames where a foot lands in a loop of L frames: contacts(f, foot) planted and not at the frame
// before, frame L - 1 coming before frame 0.
std::vector<int> loop_strikes(const Eigen::MatrixXd& contacts, int foot, int loop) {
  std::vector<int> out;
  for (int f = 0; f < loop; ++f)
    if (contacts(f, foot) > 0.5 && contacts((f + loop - 1) % loop, foot) <= 0.5) out.push_back(f);
  return out;
}

// A foot lands once per cycle: landing again sooner than the shortest cycle is not a step (the
// contact flickered, or the foot shuffles in place), and that strike is passed over; in a loop
// also across its end.
std::vector<int> debounced(const std::vector<int>& strikes, double shortest, int loop) {
  std::vector<int> kept;
  for (int f : strikes)
    if (kept.empty() || f - kept.back() >= shortest) kept.push_back(f);
  if (loop > 0 && kept.size() > 1 && kept.front() + loop - kept.back() < shortest) kept.pop_back();
  return kept;
}

// What the gait checks read of one take.
struct GaitInput {
  const Eigen::MatrixXd& local;
  double fps, leg_length;
  const CycleOptions& o;
  const GaitJoints& joints;
  int loop;                                 // L of a loop clip, else 0
  std::array<std::vector<int>, 2> strikes;  // each foot's, debounced
  // A frame of the take: in a loop, modulo L (a cycle may be read across its end).
  Eigen::Index row(int f) const {
    return loop > 0 ? ((f % loop) + loop) % loop : std::clamp<Eigen::Index>(f, 0, local.rows() - 1);
  }
};

// Whether the body walks through frames [begin, end) (read across a loop's end): the hips stay
// near standing height (above the ankles' lowest point there), and each foot moves a real
// distance against the body (the extent of its horizontal path in the canonical frame), not a
// shuffle or a shift of weight on the spot.
GaitStage body_checks(const GaitInput& in, int begin, int end) {
  const GaitJoints& j = in.joints;
  if (j.hips < 0 || j.ankles[0] < 0 || j.ankles[1] < 0) return GaitStage::kCycles;  // no body to check
  const double inf = std::numeric_limits<double>::infinity();
  double hips = inf;
  std::array<Eigen::Vector2d, 2> lo{Eigen::Vector2d::Constant(inf), Eigen::Vector2d::Constant(inf)};
  std::array<Eigen::Vector2d, 2> hi{Eigen::Vector2d::Constant(-inf), Eigen::Vector2d::Constant(-inf)};
  double floor = inf;
  for (int f = begin; f < end; ++f) {
    const Eigen::Index r = in.row(f);
    hips = std::min(hips, in.local(r, 3 * j.hips + 1));
    for (size_t side = 0; side < 2; ++side) {
      const Eigen::Index a = 3 * j.ankles[side];
      floor = std::min(floor, in.local(r, a + 1));
      const Eigen::Vector2d p(in.local(r, a), in.local(r, a + 2));
      lo[side] = lo[side].cwiseMin(p);
      hi[side] = hi[side].cwiseMax(p);
    }
  }
  if (hips - floor < in.o.min_hips_height * in.leg_length) return GaitStage::kPosture;
  for (size_t side = 0; side < 2; ++side)
    if ((hi[side] - lo[side]).norm() < in.o.min_stride * in.leg_length) return GaitStage::kStride;
  return GaitStage::kCycles;
}

// The other foot's step inside a cycle of `length` frames begun at the strike `at`: kCycles when
// it strikes once, well inside; kTogether when only near the cycle's ends; kUneven when more than
// once (a kick, a stumble: the feet do not take turns); kNoStep when not at all. In a loop, the
// other foot's strikes are read across its end.
GaitStage step_inside(const GaitInput& in, const std::vector<int>& other, int at, int length) {
  const double margin = in.o.step_share * length;
  int inside = 0, within = 0;
  bool near_ends = false;
  for (int t : other) {
    double d = t - at;
    if (in.loop > 0) d = std::fmod(std::fmod(d, in.loop) + in.loop, in.loop);
    if (d > 0 && d < length) ++within;
    if (d >= margin && d <= length - margin) ++inside;
    else if (d > -margin && d < length + margin) near_ends = true;
  }
  if (within > 1) return GaitStage::kUneven;
  if (inside == 1) return GaitStage::kCycles;
  return near_ends ? GaitStage::kTogether : GaitStage::kNoStep;
}

// One foot's gait cycles (and the furthest check they reached): from each of its strikes to its
// next, with a strike of the other foot well inside, of a plausible length, the body walking, and
// not far from the take's median cycle; a loop whose foot strikes once is the one cycle [0, L).
struct FootGait {
  std::vector<Cycle> cycles;
  GaitStage stage = GaitStage::kNoStrike;
  double strike_phase = 0.0;
};

FootGait foot_gait(const GaitInput& in, int foot) {
  FootGait out;
  const std::vector<int>& own = in.strikes[static_cast<size_t>(foot)];
  const std::vector<int>& other = in.strikes[static_cast<size_t>(1 - foot)];
  const double shortest = in.o.min_gait_s * in.fps, longest = in.o.max_gait_s * in.fps;
  auto reach = [&](GaitStage s) { out.stage = std::max(out.stage, s); };
  // A cycle of `length` frames begun at the strike `at`, over frames [begin, end): the stage it reaches.
  auto check = [&](int at, int length, int begin, int end) {
    reach(GaitStage::kLength);
    if (length < shortest || length > longest) return GaitStage::kLength;
    reach(GaitStage::kNoStep);
    const GaitStage alternation = step_inside(in, other, at, length);
    if (alternation != GaitStage::kCycles) {
      reach(alternation);
      return alternation;
    }
    reach(GaitStage::kPosture);
    const GaitStage body = body_checks(in, begin, end);
    reach(body);
    return body;
  };
  if (own.empty()) return out;
  if (in.loop > 0 && own.size() == 1) {
    if (check(own[0], in.loop, 0, in.loop) != GaitStage::kCycles) return out;
    out.cycles.push_back({0, in.loop});
    out.strike_phase = double(own[0]) / in.loop;
    out.stage = GaitStage::kCycles;
    return out;
  }
  reach(GaitStage::kOneStrike);
  std::vector<Cycle> candidates;
  for (size_t k = 0; k + 1 < own.size(); ++k) {
    const int s = own[k], e = own[k + 1];
    if (check(s, e - s, s, e + 1) == GaitStage::kCycles) candidates.push_back({s, e});
  }
  std::vector<double> lengths;
  for (const Cycle& c : candidates) lengths.push_back(c.frames());
  const double typical = median(lengths);
  for (const Cycle& c : candidates)
    if (std::abs(c.frames() - typical) <= in.o.max_change * typical) out.cycles.push_back(c);
  if (!out.cycles.empty()) out.stage = GaitStage::kCycles;
  return out;
}

// Whether the feet step in turn: one foot's strike followed by the other's a step later (more
// than step_share of the shortest cycle, less than the longest less that), twice.
bool feet_alternate(const GaitInput& in) {
  std::vector<std::pair<int, int>> merged;  // (frame, foot)
  for (int foot : {0, 1})
    for (int f : in.strikes[static_cast<size_t>(foot)]) merged.push_back({f, foot});
  std::sort(merged.begin(), merged.end());
  const double shortest = in.o.min_gait_s * in.fps, longest = in.o.max_gait_s * in.fps;
  int steps = 0;
  for (size_t k = 0; k + 1 < merged.size(); ++k) {
    const int gap = merged[k + 1].first - merged[k].first;
    if (merged[k + 1].second != merged[k].second && gap > in.o.step_share * shortest &&
        gap < (1.0 - in.o.step_share) * longest)
      ++steps;
  }
  return steps >= 2;
}

// Whether the feet land together: they strike, and each strike of either foot has one of the
// other's within step_share of the shortest cycle (a jump, or jumps, on both feet).
bool feet_land_together(const GaitInput& in) {
  const double near = in.o.step_share * in.o.min_gait_s * in.fps;
  for (int foot : {0, 1}) {
    const std::vector<int>& own = in.strikes[static_cast<size_t>(foot)];
    const std::vector<int>& other = in.strikes[static_cast<size_t>(1 - foot)];
    if (own.empty()) return false;
    for (int f : own)
      if (std::none_of(other.begin(), other.end(), [&](int t) { return std::abs(t - f) <= near; })) return false;
  }
  return true;
}

// The channels that move most (at most kPeriodicChannels, each at least o.min_amplitude of the
// leg), centred and scaled to unit spread, the one that moves most first (frames x channels);
// no columns when nothing moves (standing still).
Eigen::MatrixXd moving_channels(const Eigen::MatrixXd& local, double leg_length, const CycleOptions& o) {
  const Eigen::Index frames = local.rows();
  const Eigen::MatrixXd centred = local.rowwise() - local.colwise().mean();
  const Eigen::RowVectorXd spread = (centred.colwise().squaredNorm() / double(frames)).cwiseSqrt();
  std::vector<Eigen::Index> moving;
  for (Eigen::Index c = 0; c < spread.size(); ++c)
    if (spread[c] >= o.min_amplitude * leg_length) moving.push_back(c);
  std::sort(moving.begin(), moving.end(), [&](Eigen::Index a, Eigen::Index b) { return spread[a] > spread[b]; });
  moving.resize(std::min<size_t>(moving.size(), kPeriodicChannels));
  Eigen::MatrixXd x(frames, static_cast<Eigen::Index>(moving.size()));
  for (size_t k = 0; k < moving.size(); ++k)
    x.col(static_cast<Eigen::Index>(k)) = centred.col(moving[k]) / spread[moving[k]];
  return x;
}

// Boundaries at the minima of `anchor` (the channel that moves most), one period apart (within
// kBoundarySlack); a last cycle cut off by the take's end is left out.
std::vector<Cycle> cut_at_minima(const Eigen::VectorXd& anchor, int period) {
  const Eigen::Index frames = anchor.size();
  auto lowest = [&](Eigen::Index from, Eigen::Index to) {  // [from, to]
    Eigen::Index at = from;
    for (Eigen::Index f = from + 1; f <= to; ++f)
      if (anchor[f] < anchor[at]) at = f;
    return at;
  };
  std::vector<Cycle> cycles;
  Eigen::Index begin = lowest(0, std::min<Eigen::Index>(frames - 1, period - 1));
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
  return cycles;
}

// The cycles in which x's channels move, in each half too: cycles where the joints hardly move
// (a still start or end) are not cycles of the action.
std::vector<Cycle> moving_cycles(const Eigen::MatrixXd& x, const std::vector<Cycle>& cycles) {
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
  std::vector<Cycle> kept;
  for (size_t k = 0; k < cycles.size(); ++k)
    if (amplitude[k] >= kMinCycleAmplitude * typical && first_half[k] >= 0.5 * kMinCycleAmplitude * typical &&
        second_half[k] >= 0.5 * kMinCycleAmplitude * typical)
      kept.push_back(cycles[k]);
  return kept;
}

// local less its moving average over kStrokeTrendS: the strokes of a hand waved with the arm
// raised, without the raising and lowering that would hide them from the autocorrelation.
constexpr double kStrokeTrendS = 1.2;
Eigen::MatrixXd detrended(const Eigen::MatrixXd& local, double fps) {
  const Eigen::Index frames = local.rows();
  const Eigen::Index half = std::max<Eigen::Index>(1, std::lround(0.5 * kStrokeTrendS * fps));
  Eigen::MatrixXd prefix = Eigen::MatrixXd::Zero(frames + 1, local.cols());
  for (Eigen::Index f = 0; f < frames; ++f) prefix.row(f + 1) = prefix.row(f) + local.row(f);
  Eigen::MatrixXd out(frames, local.cols());
  for (Eigen::Index f = 0; f < frames; ++f) {
    const Eigen::Index lo = std::max<Eigen::Index>(0, f - half), hi = std::min(frames, f + half + 1);
    out.row(f) = local.row(f) - (prefix.row(hi) - prefix.row(lo)) / double(hi - lo);
  }
  return out;
}

// The period of one stroke of the joint that moves most (x: its detrended channel): the first
// lag, past the first where it swings the other way (its correlation below 0), at which it comes
// back, correlating at least kStrokePeriodicity with itself; -1 when it does not. Read on the one
// channel, so channels swinging out of phase (a hand's x and y) do not cancel.
constexpr double kStrokePeriodicity = 0.3;
int stroke_period(const Eigen::VectorXd& x, double fps, const CycleOptions& o) {
  const Eigen::Index frames = x.size();
  const int min_lag = std::max(2, static_cast<int>(std::lround(o.min_period_s * fps)));
  const int max_lag = std::min(static_cast<int>(std::lround(o.max_period_s * fps)), static_cast<int>(frames / 2));
  if (max_lag <= min_lag + 1) return -1;
  auto r = [&](int lag) {
    const Eigen::Index n = frames - lag;
    const auto a = x.head(n), b = x.tail(n);
    const double d = std::sqrt(a.squaredNorm() * b.squaredNorm());
    return d > 0 ? a.dot(b) / d : 0.0;
  };
  bool swung = false;
  double previous = r(min_lag - 1), here = r(min_lag);
  for (int lag = min_lag; lag < max_lag; ++lag) {
    const double next = r(lag + 1);
    if (here < 0) swung = true;
    if (swung && here >= previous && here >= next && here >= kStrokePeriodicity) return lag;
    previous = here;
    here = next;
  }
  return -1;
}

// The strokes of the take's moving span: the period of its most moving joint (read on the span
// alone, so the rests around it do not dilute the repeats), two or more; none for a one-shot action.
TakeCycles strokes_of_action(const Eigen::MatrixXd& local, const ActionSpans& spans, double fps, double leg_length,
                             const CycleOptions& o) {
  const FrameSpan active = spans.active();
  if (active.frames() < 4) return {};
  const Eigen::MatrixXd x = moving_channels(detrended(local.middleRows(active.begin, active.frames()), fps), leg_length, o);
  if (x.cols() == 0) return {};
  const int period = stroke_period(x.col(0), fps, o);
  if (period < 0) return {};
  TakeCycles out;
  out.cycles = moving_cycles(x, cut_at_minima(x.col(0), period));
  if (out.cycles.size() < 2) return {};
  out.kind = CycleKind::kPeriodic;
  out.period = period;
  for (Cycle& c : out.cycles) {
    c.begin += active.begin;
    c.end += active.begin;
  }
  return out;
}

// A loop clip that is no gait: its one cycle [0, L) when some joint moves (min_amplitude) and the
// loop is as long as a period may be (up to kMaxLoopCycles of the longest), else none.
TakeCycles loop_period(const Eigen::MatrixXd& local, int loop, double fps, double leg_length, const CycleOptions& o) {
  TakeCycles out;
  const double seconds = loop / fps;
  if (seconds < o.min_period_s || seconds > kMaxLoopCycles * o.max_period_s) return out;
  const auto frames = local.topRows(loop);
  const Eigen::RowVectorXd spread =
      ((frames.rowwise() - frames.colwise().mean()).colwise().squaredNorm() / double(loop)).cwiseSqrt();
  if (!(spread.maxCoeff() > 0.0) || spread.maxCoeff() < o.min_amplitude * leg_length) return out;  // still
  out.kind = CycleKind::kPeriodic;
  out.cycles.push_back({0, loop});
  out.period = loop;
  return out;
}

int frames_in(const std::vector<Cycle>& cycles) {
  int n = 0;
  for (const Cycle& c : cycles) n += c.frames();
  return n;
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
  if (!(min_amplitude >= 0.0) || !std::isfinite(min_amplitude))
    throw InputError("cycle detection: the smallest amplitude must be a number from 0 up");
  if (foot < -1 || foot > 1) throw InputError("cycle detection: the foot must be left (0), right (1) or either (-1)");
  if (!(step_share >= 0.0 && step_share < 0.5))
    throw InputError("cycle detection: the share of a cycle kept clear of the other foot's step must be from 0, below 1/2");
  for (double v : {min_hips_height, min_stride})
    if (!(v >= 0.0) || !std::isfinite(v))
      throw InputError("cycle detection: the hips' least height and the least stride must be numbers from 0 up");
}

int TakeCycles::frames_in_cycles() const {
  int n = 0;
  for (const Cycle& c : cycles) n += c.frames();
  return n;
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

int cycle_loop_frames(const Eigen::MatrixXd& local, double fps, const ActionSpans& spans, const CycleOptions& options) {
  if (spans.still() || spans.rests_at_both_ends()) return 0;
  const int longest = static_cast<int>(std::floor(kMaxLoopCycles * options.max_gait_s * fps));
  return loop_clip_frames(local, longest, kMaxLoopCycles - 1);
}

int cycle_loop_frames(const Eigen::MatrixXd& local, double fps, double leg_length, const CycleOptions& options) {
  return cycle_loop_frames(local, fps, find_action_spans(local, fps, leg_length), options);
}

TakeCycles detect_cycles(const Eigen::MatrixXd& contacts, const Eigen::MatrixXd& local, double fps, double leg_length,
                         const CycleOptions& options, const GaitJoints& joints) {
  options.Validate();
  if (contacts.cols() != 2 || contacts.rows() != local.rows())
    throw InputError("cycle detection: expected two feet's contacts for each of the take's " +
                     std::to_string(local.rows()) + " frames, found " + std::to_string(contacts.rows()) + " x " +
                     std::to_string(contacts.cols()));
  if (!(fps > 0.0) || !(leg_length > 0.0))
    throw InputError("cycle detection: the frame rate and the leg length must be above 0");
  for (int j : {joints.hips, joints.ankles[0], joints.ankles[1]})
    if (j < -1 || 3 * static_cast<Eigen::Index>(j) + 2 >= local.cols())
      throw InputError("cycle detection: joint " + std::to_string(j) + " is not among the take's " +
                       std::to_string(local.cols() / 3) + " joints");
  const ActionSpans spans = find_action_spans(local, fps, leg_length);
  const int loop = cycle_loop_frames(local, fps, spans, options);
  GaitInput in{local, fps, leg_length, options, joints, loop, {}};
  for (int foot : {0, 1}) {
    const std::vector<int> strikes = loop > 0 ? loop_strikes(contacts, foot, loop) : foot_strikes(contacts, foot);
    in.strikes[static_cast<size_t>(foot)] = debounced(strikes, options.min_gait_s * fps, loop);
  }

  TakeCycles out;
  out.loop_frames = loop;
  out.spans = spans;
  FootGait best;
  int best_foot = options.foot >= 0 ? options.foot : 0;
  for (int foot : {0, 1}) {
    if (options.foot >= 0 && foot != options.foot) continue;
    FootGait g = foot_gait(in, foot);
    const bool more = g.cycles.size() > best.cycles.size() ||
                      (g.cycles.size() == best.cycles.size() && !g.cycles.empty() &&
                       frames_in(g.cycles) > frames_in(best.cycles));
    if (more || (best.cycles.empty() && g.cycles.empty() && g.stage > best.stage)) {
      best = std::move(g);
      best_foot = foot;
    }
  }
  const bool lone_step = loop == 0 && best.cycles.size() == 1 &&
                         best.cycles[0].frames() < kLoneGaitShare * spans.active().frames();
  if (!best.cycles.empty() && !lone_step) {
    out.kind = CycleKind::kGait;
    out.cycles = std::move(best.cycles);
    out.foot = best_foot;
    out.strike_phase = best.strike_phase;
    std::vector<double> lengths;
    for (const Cycle& c : out.cycles) lengths.push_back(c.frames());
    out.period = median(lengths);
    return out;
  }
  // Feet that land together say so, however far the cycles got (one jump strikes each foot once).
  const GaitStage got = best.stage < GaitStage::kTogether && feet_land_together(in) ? GaitStage::kTogether : best.stage;
  const std::string why = lone_step ? "one step inside another action, not a walk" : gait_reason(got, best_foot, options);
  if (feet_alternate(in) && !lone_step) {  // a gait that fails its checks is no other repeated action either
    out.reason = why;
    return out;
  }
  TakeCycles periodic = loop > 0 ? loop_period(local, loop, fps, leg_length, options)
                                 : strokes_of_action(local, spans, fps, leg_length, options);
  periodic.loop_frames = loop;
  periodic.spans = spans;
  periodic.reason = periodic.kind == CycleKind::kNone ? why + "; nothing else repeats" : why;
  return periodic;
}

std::string action_structure_summary(const TakeCycles& cycles, double fps) {
  const ActionSpans& spans = cycles.spans;
  auto at = [&](double frame) {
    char s[32];
    std::snprintf(s, sizeof s, "%.1f", frame / fps);
    return std::string(s);
  };
  auto span = [&](const FrameSpan& f) { return at(f.begin) + "-" + at(f.end) + " s"; };
  const int n = static_cast<int>(cycles.cycles.size());
  if (cycles.kind == CycleKind::kGait)
    return "gait: " + std::to_string(n) + (n == 1 ? " cycle" : " cycles") + (cycles.foot == 0 ? " (left foot)" : " (right foot)") +
           (cycles.loops() ? ", a loop" : "");
  if (cycles.kind == CycleKind::kPeriodic && cycles.loops()) {
    char s[64];
    std::snprintf(s, sizeof s, "periodic: a loop of %.2f s", cycles.loop_frames / fps);
    return s + (spans.mover_part.empty() ? std::string() : " of the " + spans.mover_part);
  }
  if (spans.still()) return "at rest throughout";
  std::string rests;
  if (spans.rests_at_both_ends()) rests = " between rests";
  else if (spans.rest_before > 0) rests = ", a rest before";
  else if (spans.rest_after > 0) rests = ", a rest after";
  if (cycles.kind == CycleKind::kPeriodic) {
    const FrameSpan strokes{cycles.cycles.front().begin, cycles.cycles.back().end};
    return "periodic: " + std::to_string(n) + " strokes" +
           (spans.mover_part.empty() ? std::string() : " of the " + spans.mover_part) + " (" + span(strokes) + ")" + rests;
  }
  const size_t actions = spans.actions.size();
  std::string s = (actions == 1 ? std::string("one action") : std::to_string(actions) + " actions");
  if (!spans.mover_part.empty() && spans.mover_part != "body") s += " of the " + spans.mover_part;
  s += " (";
  for (size_t k = 0; k < actions; ++k) s += (k > 0 ? ", " : "") + span(spans.actions[k]);
  return s + ")" + rests;
}

}  // namespace mostyle
