#include "engine/live/live_phase.h"

#include <algorithm>
#include <cmath>

#include "engine/kinematics/ease.h"

namespace mostyle {
namespace {

// The phase shown advances at least this and at most that many times the prediction's rate while
// it closes an error: it never stops or runs backwards, and a large error (a strike much earlier
// or later than predicted) is closed within a fraction of a cycle.
constexpr double kSlowestCatchUp = 0.25;
constexpr double kFastestCatchUp = 4.0;
// After a strike of the other foot, the cycle foot's next strike is expected no sooner than this
// share of the rest of the cycle.
constexpr double kShortestRest = 0.25;

// x - round(x): in [-0.5, 0.5].
double wrapped(double x) { return x - std::round(x); }

}  // namespace

LivePhase::LivePhase(const LivePhaseOptions& options) : o_(options) {
  other_share_ = o_.other_strike_phase;
}

double LivePhase::phase() const { return shown_ - std::floor(shown_); }

double LivePhase::predicted_phase() const {
  const double p = anchor_phase_ + double(frame_ - anchor_frame_) * rate_;
  return p - std::floor(p);
}

double LivePhase::typical_period() const {
  // The median of at most five: an insertion sort.
  std::array<double, 5> sorted = recent_;
  const size_t n = static_cast<size_t>(std::min(recent_count_, static_cast<int>(sorted.size())));
  for (size_t i = 1; i < n; ++i)
    for (size_t k = i; k > 0 && sorted[k - 1] > sorted[k]; --k) std::swap(sorted[k - 1], sorted[k]);
  return n > 0 ? sorted[n / 2] : 0.0;
}

void LivePhase::set_prediction(long at, double phase, double rate) {
  anchor_frame_ = at;
  anchor_phase_ = phase;
  rate_ = rate;
}

void LivePhase::strike_cycle_foot(long at) {
  const int cycle = o_.cycle_foot, other = 1 - cycle;
  const double min_stride = o_.cycles.min_stride * o_.leg_length;
  const bool stride = stride_[static_cast<size_t>(cycle)] >= min_stride;
  bool passes = false;
  if (last_cycle_strike_ >= 0) {
    // The cycle this strike ends, against the offline checks (cycles.h).
    const double length = double(at - last_cycle_strike_);
    const bool in_range = length >= o_.cycles.min_gait_s * o_.fps && length <= o_.cycles.max_gait_s * o_.fps;
    double typical = length;
    if (in_range) {
      if (recent_count_ > 0) typical = typical_period();
      recent_[static_cast<size_t>(recent_count_ % static_cast<int>(recent_.size()))] = length;
      ++recent_count_;
    }
    const bool steady = in_range && std::abs(length / typical - 1.0) <= o_.cycles.max_change;
    const double share = double(last_other_strike_ - last_cycle_strike_) / length;
    const bool in_step = last_other_strike_ > last_cycle_strike_ && share >= o_.cycles.step_share &&
                         share <= 1.0 - o_.cycles.step_share;
    passes = steady && in_step && stride && stride_[static_cast<size_t>(other)] >= min_stride;
    if (passes) {
      period_ = length;
      other_share_ = has_other_share_ ? 0.5 * (other_share_ + share) : share;
      has_other_share_ = true;
      ++cycles_;
    }
  }
  // A first step after standing (no strike of this foot within the gait's longest cycle) that
  // reaches as a walk's does starts walking; a cycle that fails the checks ends it.
  const bool first_step = last_cycle_strike_ < 0 || double(at - last_cycle_strike_) > o_.cycles.max_gait_s * o_.fps;
  in_cycle_ = passes || (first_step && (stride || in_cycle_));
  last_cycle_strike_ = at;
  cycle_clock_ = at;
  if (stride) set_prediction(at, 0.0, 1.0 / (period_ > 0.0 ? period_ : o_.guess_period_s * o_.fps));
}

void LivePhase::strike_other_foot(long at) {
  const int other = 1 - o_.cycle_foot;
  last_other_strike_ = at;
  if (stride_[static_cast<size_t>(other)] < o_.cycles.min_stride * o_.leg_length) return;
  const double reference = period_ > 0.0 ? period_ : o_.guess_period_s * o_.fps;
  if (last_cycle_strike_ < 0 || double(at - last_cycle_strike_) > o_.cycles.max_gait_s * o_.fps) {
    // A first step after standing, of the other foot: walking from here, at the other foot's
    // phase, the cycle foot expected a cycle's share later.
    if (in_cycle_) return;
    in_cycle_ = true;
    cycle_clock_ = static_cast<long>(std::lround(double(at) - other_share_ * reference));
    set_prediction(at, o_.other_strike_phase, (1.0 - o_.other_strike_phase) / ((1.0 - other_share_) * reference));
    return;
  }
  // The cycle this step says, from the stream's own share of a cycle before the other foot lands.
  const double step = double(at - last_cycle_strike_);
  const double now = step / other_share_;
  const bool in_step = now >= o_.cycles.min_gait_s * o_.fps && now <= o_.cycles.max_gait_s * o_.fps &&
                       (period_ <= 0.0 || std::abs(now / reference - 1.0) <= o_.cycles.max_change);
  // The foot says where in the cycle the stream is, in step or not (phases matched by foot);
  // only a step in time says it walks, and how long this cycle will be.
  if (in_step) in_cycle_ = true;
  const double expected = period_ > 0.0 && in_step ? 0.5 * (reference + now) : in_step ? now : reference;
  const double rest = std::max(double(last_cycle_strike_) + expected - double(at),
                               kShortestRest * (1.0 - other_share_) * expected);
  set_prediction(at, o_.other_strike_phase, (1.0 - o_.other_strike_phase) / rest);
}

void LivePhase::update(const std::array<long, 2>& strikes, const std::array<Eigen::Vector2d, 2>& ankles) {
  const long t = ++frame_;
  for (size_t side = 0; side < 2; ++side) {
    if (!reach_seen_[side]) reach_min_[side] = reach_max_[side] = ankles[side];
    reach_seen_[side] = true;
    reach_min_[side] = reach_min_[side].cwiseMin(ankles[side]);
    reach_max_[side] = reach_max_[side].cwiseMax(ankles[side]);
  }
  // This frame's strikes, the earlier first: each foot's reach since its strike before.
  int order[2] = {0, 1};
  if (strikes[1] >= 0 && (strikes[0] < 0 || strikes[1] < strikes[0])) std::swap(order[0], order[1]);
  for (int side : order) {
    const size_t s = static_cast<size_t>(side);
    if (strikes[s] < 0) continue;
    stride_[s] = (reach_max_[s] - reach_min_[s]).norm();
    reach_min_[s] = reach_max_[s] = ankles[s];
    if (side == o_.cycle_foot) strike_cycle_foot(strikes[s]);
    else strike_other_foot(strikes[s]);
  }
  const double expected = period_ > 0.0 ? period_ : o_.guess_period_s * o_.fps;
  if (in_cycle_ && double(t - cycle_clock_) > (1.0 + o_.cycles.max_change) * expected) in_cycle_ = false;
  // A step missed: no strike of either foot for missed_step times the step expected since the
  // last (a foot that drags or shuffles, a stumble), where offline the cycle would fail its checks.
  const long last = std::max(last_cycle_strike_, last_other_strike_);
  const double step = (last == last_cycle_strike_ ? other_share_ : 1.0 - other_share_) * expected;
  if (in_cycle_ && last >= 0 && double(t - last) > o_.missed_step * step) in_cycle_ = false;
  fade_ = std::clamp(fade_ + (in_cycle_ ? 1.0 : -1.0) / std::max(1.0, o_.fade_cycles * expected), 0.0, 1.0);
  weight_ = smoothstep(fade_);
  // The phase shown: the prediction itself while it is not seen (weight 0), else one frame on at
  // the prediction's rate plus a share of the error, within the catch-up limits.
  const double predicted = anchor_phase_ + double(t - anchor_frame_) * rate_;
  if (weight_ == 0.0 || t == 0) {
    shown_ = predicted;
  } else {
    const double frames = std::max(1.0, o_.correction_seconds * o_.fps);
    const double step = rate_ + wrapped(predicted - shown_ - rate_) / frames;
    shown_ += std::clamp(step, kSlowestCatchUp * rate_, kFastestCatchUp * rate_);
  }
  shown_ -= std::floor(shown_);
}

}  // namespace mostyle
