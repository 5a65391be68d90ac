#include "engine/trajectory/mixed_clock.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/base/error.h"

namespace mostyle {

namespace {

// Output frame f at the sample position where the clock reaches f; step(k) is the clock's
// advance from sample k - 1 to k (negative advances hold). Where the clock does not move at the
// start (a take's start its weights give no time: a longer start of a take held against the
// reference's first frame, on the reference's clock), the first frame is where it starts to
// move, so that the next frame does not leap over the stretch. One pass to count the frames,
// one to place them: nothing is allocated but u.
template <typename Step>
ClockEnd timeline_from_steps(int samples, const Step& step, Eigen::VectorXd& u) {
  ClockEnd end;
  double& total = end.clock;
  for (int k = 1; k < samples; ++k) {
    const double advance = std::max(0.0, step(k));
    total += advance;
    if (advance > 0.0) end.sample = k;
  }
  const int frames = static_cast<int>(std::floor(total + 1e-9)) + 1;
  u.resize(frames);
  int k = 0;
  if (total > 0.0)
    while (k + 2 < samples && !(step(k + 1) > 0.0)) ++k;
  double before = 0.0, after = 0.0;  // clock at samples k and k + 1
  if (samples > 1) after = std::max(0.0, step(k + 1));
  for (int f = 0; f < frames; ++f) {
    while (k + 1 < samples - 1 && after < f) {
      ++k;
      before = after;
      after += std::max(0.0, step(k + 1));
    }
    if (samples == 1) {
      u[f] = 0.0;
      continue;
    }
    const double span = after - before;
    u[f] = k + (span > 0 ? std::clamp((f - before) / span, 0.0, 1.0) : 0.0);
  }
  return end;
}

}  // namespace

namespace {

void check_stretch(const CommonTimeline& timeline, int first, int last) {
  if (first < 0 || last < first || last >= timeline.samples())
    throw InputError("cannot time a mix over samples " + std::to_string(first) + " to " + std::to_string(last) +
                     " of a timeline of " + std::to_string(timeline.samples()));
}

// The clock's advance from sample k - 1 to k (absolute samples) with one weight per take. Never
// slower than the slowest take with a weight: a negative weight (a transfer's -s on the neutral
// take) could stall the clock, and the output would then run through the takes' frames faster
// than any of them moves. Weights within [0, 1] never reach the bound.
template <typename Weight>
double mixed_step(const CommonTimeline& timeline, const Weight& weight, int k) {
  double step = 0.0, slowest = INFINITY;
  for (int i = 0; i < timeline.takes(); ++i) {
    const double advance = timeline.frames[static_cast<size_t>(i)][k] - timeline.frames[static_cast<size_t>(i)][k - 1];
    const double w = weight(i);
    step += w * advance;
    if (w != 0.0) slowest = std::min(slowest, advance);
  }
  return std::max(step, slowest);
}

// Whether slot s lies inside the stretch (a slot the stretch cuts always plays).
bool inside(const CycleSlots::Slot& slot, SampleSpan span) { return slot.first >= span.first && slot.last <= span.last; }

// Whether slot s plays: the reference's own slots alone when asked; else, while the reference
// has a weight, each of its own cycles (all of the reference plays at every weight below 1), and
// the slots it plays again as the weights' own cycles call for them (SlotCount); at its weight 0,
// every slot by the count, so that the takes weighted play their own.
template <typename Weight>
bool slot_plays(const SlotPlay& play, int s, int takes, const Weight& weight, SlotCount& count) {
  const Eigen::MatrixXd& own = play.slots->own;
  if (play.reference_only) return own(s, 0) > 0.5;
  if (weight(0) > 0.0 && own(s, 0) > 0.5) return true;
  double share = 0.0;
  for (int i = 0; i < takes; ++i) share += weight(i) * own(s, i);
  return count.play(share);
}

// Whether the clock's advance into sample k (absolute) is left out: k inside a skipped slot,
// after its first sample. skipped: slot indices in order.
bool skipped_step(const SlotPlay& play, const std::vector<int>& skipped, int k) {
  const auto at = std::upper_bound(skipped.begin(), skipped.end(), k, [&](int sample, int s) {
    return sample <= play.slots->slots[static_cast<size_t>(s)].first;
  });
  if (at == skipped.begin()) return false;
  return k <= play.slots->slots[static_cast<size_t>(*std::prev(at))].last;
}

}  // namespace

void mixed_timeline(const CommonTimeline& timeline, const std::vector<double>& weights, SampleSpan span,
                    Eigen::VectorXd& u, ClockEnd* end, const SlotPlay& slots) {
  const int first = span.first, last = span.last;
  if (static_cast<int>(weights.size()) != timeline.takes())
    throw InputError("expected " + std::to_string(timeline.takes()) + " timing weights, found " +
                     std::to_string(weights.size()));
  for (double w : weights)
    if (!std::isfinite(w)) throw InputError("expected finite timing weights");
  check_stretch(timeline, first, last);
  std::vector<int> none;
  std::vector<int>& skipped = slots.skipped != nullptr ? *slots.skipped : none;
  skipped.clear();
  if (slots.slots != nullptr) {
    SlotCount count;
    for (int s = 0; s < slots.slots->size(); ++s) {
      const bool in = inside(slots.slots->slots[static_cast<size_t>(s)], span);
      if (!slot_plays(slots, s, timeline.takes(), [&](int i) { return weights[static_cast<size_t>(i)]; }, count) && in)
        skipped.push_back(s);
    }
  }
  ClockEnd reached = timeline_from_steps(
      last - first + 1,
      [&](int k) {
        if (!skipped.empty() && skipped_step(slots, skipped, first + k)) return 0.0;
        return mixed_step(timeline, [&](int i) { return weights[static_cast<size_t>(i)]; }, first + k);
      },
      u);
  u.array() += first;
  reached.sample += first;
  if (end != nullptr) *end = reached;
}

void mixed_timeline(const CommonTimeline& timeline, const WeightKeys& keys, double fps, SampleSpan span,
                    Eigen::VectorXd& u, Eigen::MatrixXd* sample_weights, ClockEnd* end, const SlotPlay& slots) {
  const int first = span.first, last = span.last;
  validate_keys(keys, timeline.takes());
  if (keys.empty()) throw InputError("cannot time a mix by keys without a key");
  if (!(fps > 0.0) || !std::isfinite(fps)) throw InputError("expected a frame rate above 0 to time keys in seconds");
  check_stretch(timeline, first, last);
  const int samples = last - first + 1;
  Eigen::VectorXd steps = Eigen::VectorXd::Zero(samples);
  std::vector<double> w;
  double clock = 0.0;
  if (sample_weights != nullptr) sample_weights->resize(samples, timeline.takes());
  std::vector<int> none;
  std::vector<int>& skipped = slots.skipped != nullptr ? *slots.skipped : none;
  skipped.clear();
  SlotCount count;
  int next_slot = 0, skip_to = -1;  // the next slot to decide; the last sample of a slot being left out
  const int slot_count = slots.slots != nullptr ? slots.slots->size() : 0;
  for (int k = 0; k < samples; ++k) {
    weights_at(keys, clock / fps, w);
    for (double x : w)
      if (!std::isfinite(x)) throw InputError("expected finite timing weights");
    if (sample_weights != nullptr)
      for (int i = 0; i < timeline.takes(); ++i) (*sample_weights)(k, i) = w[static_cast<size_t>(i)];
    // Slots that begin here (or began before the stretch) are decided with the weights now.
    while (next_slot < slot_count && slots.slots->slots[static_cast<size_t>(next_slot)].first <= first + k) {
      const CycleSlots::Slot& slot = slots.slots->slots[static_cast<size_t>(next_slot)];
      const bool play = slot_plays(slots, next_slot, timeline.takes(), [&](int i) { return w[static_cast<size_t>(i)]; }, count);
      if (!play && inside(slot, span)) {
        skipped.push_back(next_slot);
        skip_to = slot.last;
      }
      ++next_slot;
    }
    if (k + 1 < samples) {
      steps[k + 1] = first + k + 1 <= skip_to ? 0.0 : mixed_step(timeline, [&](int i) { return w[static_cast<size_t>(i)]; }, first + k + 1);
      clock += std::max(0.0, steps[k + 1]);
    }
  }
  ClockEnd reached = timeline_from_steps(samples, [&](int k) { return steps[k]; }, u);
  u.array() += first;
  reached.sample += first;
  if (end != nullptr) *end = reached;
}

void land_on_last(Eigen::VectorXd& u, double last, double clock_at_last) {
  const Eigen::Index k = u.size();
  if (k < 2) return;
  // The clock's end: at frame k - 1 it is at u's last, at clock_at_last (not below) on `last`.
  const double reach = std::max(clock_at_last, double(k - 1));
  const Eigen::Index frames = std::max<Eigen::Index>(2, std::lround(reach) + 1);
  const Eigen::VectorXd clock = u;
  u.resize(frames);
  for (Eigen::Index j = 0; j < frames; ++j) {
    const double x = double(j) * reach / double(frames - 1);
    if (x >= double(k - 1)) {  // between u's last frame and the clock's end
      const double tail = reach - double(k - 1);
      u[j] = tail > 0.0 ? clock[k - 1] + (x - double(k - 1)) / tail * (last - clock[k - 1]) : last;
      continue;
    }
    const Eigen::Index r = std::min<Eigen::Index>(static_cast<Eigen::Index>(x), k - 2);
    u[j] = clock[r] + (x - double(r)) * (clock[r + 1] - clock[r]);
  }
  u[frames - 1] = last;
}

}  // namespace mostyle
