#include "engine/trajectory/mixed_trajectory.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/base/error.h"
#include "engine/base/weighted_sum.h"
#include "engine/trajectory/mixed_clock.h"
#include "engine/trajectory/mixed_root.h"

namespace mostyle {
namespace {

// Whether samples first..last show a loop reference's whole loop: its one cycle from its first
// frame to its last (the loop's end: prepare_takes gives a loop reference that frame).
bool shows_whole_loop(const PreparedTakes& p, int first, int last) {
  const PreparedTake& r = p.reference();
  const Eigen::Index frames = r.own_local_t.cols();
  if (!r.cycles.loops() || r.cycles.loop_frames != frames - 1) return false;
  return r.frames[first] <= 0.0 && r.frames[last] >= double(frames - 1);
}

// The ground path's travel from its first sample to sample `end` (where the loop ends, the
// clock's end) made the path's own (x, z), the difference taken away in even shares along it and
// in full after it. ground, path: U x 2. O(U).
void keep_loop_travel(Eigen::MatrixXd& ground, const Eigen::Ref<const Eigen::MatrixXd>& path, Eigen::Index end) {
  const Eigen::Index n = ground.rows();
  if (n < 2 || path.rows() != n || end < 1 || end >= n) return;
  const Eigen::RowVector2d off = (ground.row(end) - ground.row(0)) - (path.row(end) - path.row(0));
  for (Eigen::Index k = 1; k < n; ++k) ground.row(k) -= (double(std::min(k, end)) / double(end)) * off;
}

// A path over the stretch (rows counted from sample `first`) with the slots left out closed up:
// over each, it stays where the slot begins, and after it goes on moved rigidly (turned by the
// heading's change over the slot, when given, and moved back by the slot's travel). ground: U x 2;
// heading: U or null, then the turns over each slot when given (a path without a heading of its
// own: the weighted one, turned as the weighted steps turn). O(U x skipped).
void close_skipped(const CycleSlots& slots, const std::vector<int>& skipped, int first, Eigen::MatrixXd& ground,
                   Eigen::VectorXd* heading, const std::vector<double>* turns = nullptr) {
  const Eigen::Index n = ground.rows();
  for (size_t j = 0; j < skipped.size(); ++j) {
    const int slot = skipped[j];
    const Eigen::Index a = slots.slots[static_cast<size_t>(slot)].first - first, b = slots.slots[static_cast<size_t>(slot)].last - first;
    if (a < 0 || b >= n || b <= a) continue;
    const double turn = heading != nullptr ? (*heading)[b] - (*heading)[a] : turns != nullptr ? (*turns)[j] : 0.0;
    // integrate_root turns a body-frame step by -heading into the world: undoing a turn turns by +turn.
    const double c = std::cos(turn), sn = std::sin(turn);
    const Eigen::RowVector2d from = ground.row(b), to = ground.row(a);
    for (Eigen::Index k = a + 1; k < n; ++k) {
      if (k <= b) {
        ground.row(k) = to;
        if (heading != nullptr) (*heading)[k] = (*heading)[a];
        continue;
      }
      const Eigen::RowVector2d d = ground.row(k) - from;
      ground(k, 0) = to[0] + c * d[0] - sn * d[1];
      ground(k, 1) = to[1] + sn * d[0] + c * d[1];
      if (heading != nullptr) (*heading)[k] -= turn;
    }
  }
}

// The rows of a stretch (length rows from sample `first`) that are played: all but those inside
// a skipped slot after its first sample. O(length).
void played_rows(const CycleSlots& slots, const std::vector<int>& skipped, Eigen::Index first, Eigen::Index length,
                 std::vector<Eigen::Index>& kept) {
  kept.clear();
  size_t next = 0;
  for (Eigen::Index r = 0; r < length; ++r) {
    while (next < skipped.size() && slots.slots[static_cast<size_t>(skipped[next])].last - first < r) ++next;
    const bool inside = next < skipped.size() && slots.slots[static_cast<size_t>(skipped[next])].first - first < r &&
                        r <= slots.slots[static_cast<size_t>(skipped[next])].last - first;
    if (!inside) kept.push_back(r);
  }
}

// out.row(j) = m.row(kept[j]).
template <typename M>
void keep_rows(const M& m, const std::vector<Eigen::Index>& kept, M& out) {
  out.resize(static_cast<Eigen::Index>(kept.size()), m.cols());
  for (size_t j = 0; j < kept.size(); ++j) out.row(static_cast<Eigen::Index>(j)) = m.row(kept[j]);
}

// Steps (rows: sample r to r + 1) from each kept row to the next kept: the steps between them summed.
void summed_steps(const Eigen::MatrixXd& steps, const std::vector<Eigen::Index>& kept, Eigen::MatrixXd& out) {
  out.setZero(static_cast<Eigen::Index>(kept.size()), steps.cols());
  for (size_t j = 0; j < kept.size(); ++j) {
    const Eigen::Index end = j + 1 < kept.size() ? kept[j + 1] : kept[j] + 1;
    for (Eigen::Index r = kept[j]; r < end && r < steps.rows(); ++r) out.row(static_cast<Eigen::Index>(j)) += steps.row(r);
  }
}

// The played rows spread back over the stretch's length rows: a row left out holds the last
// played row before it.
template <typename M>
void spread_rows(const M& m, const std::vector<Eigen::Index>& kept, Eigen::Index length, M& out) {
  out.resize(length, m.cols());
  size_t j = 0;
  for (Eigen::Index r = 0; r < length; ++r) {
    while (j + 1 < kept.size() && kept[j + 1] <= r) ++j;
    out.row(r) = m.row(static_cast<Eigen::Index>(j));
  }
}

// out = sum_i w_i (take i's `member`, rows [first, first + length)), a column at a time in one
// pass (the same sums as setZero and one += per take).
void weighted_columns(const PreparedTakes& p, const std::vector<double>& w, Eigen::MatrixXd PreparedTake::*member,
                      Eigen::Index first, Eigen::Index length, std::vector<WeightedTerm>& terms, Eigen::MatrixXd& out) {
  const Eigen::Index columns = (p.takes.front().*member).cols();
  out.resize(length, columns);
  terms.resize(static_cast<size_t>(p.size()));
  for (Eigen::Index c = 0; c < columns; ++c) {
    for (int i = 0; i < p.size(); ++i) terms[static_cast<size_t>(i)] = {w[static_cast<size_t>(i)], (p.takes[i].*member).col(c).data() + first};
    weighted_sum(terms.data(), p.size(), length, out.col(c).data());
  }
}

}  // namespace

PlayedStretch played_stretch(const PreparedTakes& p, const std::vector<double>& weights, const WeightKeys& keys,
                             const Eigen::MatrixXd& component_weights, bool per_component,
                             const std::vector<double>& timing) {
  PlayedStretch st;
  st.last = p.samples() - 1;
  for (int i = 0; i < p.size(); ++i) {
    bool weighted = weights[i] != 0.0 || timing[i] != 0.0;
    for (const WeightKey& key : keys) weighted |= key.weights[static_cast<size_t>(i)] != 0.0;
    for (Eigen::Index c = 0; per_component && c < component_weights.rows(); ++c)
      weighted |= component_weights(c, i) != 0.0;
    if (!weighted) continue;
    st.fastest = std::max(st.fastest, p.takes[static_cast<size_t>(i)].fastest_joint);
    st.first = std::max(st.first, p.timeline.first[i]);
    st.last = std::min(st.last, p.timeline.last[i]);
  }
  if (st.first >= st.last)
    throw InputError("the takes given a weight match no common stretch of the reference (each matched a "
                     "different part of it); give weight to takes whose matches overlap, or align them end to "
                     "end (closed ends)");
  return st;
}

FinishOptions output_clock(const PreparedTakes& p, const ClockWeights& weights, const FinishOptions& options,
                           const PlayedStretch& st, MixedTrajectory& s, Eigen::MatrixXd& sources) {
  const WeightKeys& keys = *weights.keys;
  const std::vector<double>& timing = *weights.timing;
  const int n = p.size();
  const bool keyed = !keys.empty();
  ClockEnd end;
  SlotPlay slots;
  slots.slots = p.slots.empty() ? nullptr : &p.slots;
  slots.reference_only = weights.reference_cycles || weights.reference_timing;
  slots.skipped = &s.skipped;
  if (keyed && !weights.reference_timing) {
    mixed_timeline(p.timeline, keys, p.fps, {st.first, st.last}, s.u, &s.sample_w, &end, slots);
  } else {
    mixed_timeline(p.timeline, timing, {st.first, st.last}, s.u, &end, slots);
    if (keyed) {  // the reference's clock: each sample's weights at the reference's time there
      s.sample_w.resize(st.length(), n);
      std::vector<double> w;
      const Eigen::VectorXd& clock = p.timeline.frames[0];
      for (Eigen::Index k = 0; k < st.length(); ++k) {
        weights_at(keys, (clock[st.first + k] - clock[st.first]) / p.fps, w);
        for (int i = 0; i < n; ++i) s.sample_w(k, i) = w[static_cast<size_t>(i)];
      }
    }
  }
  FinishOptions finish = options;
  finish.closed = shows_whole_loop(p, st.first, st.last);
  if (finish.closed) {
    land_on_last(s.u, end.sample, end.clock);
    finish.loop = false;
  }
  s.u_stretch = s.u.array() - double(st.first);
  s.sampler.set(s.u_stretch, st.length());
  // Where each slot left out is: the first output frame at or past its last sample.
  s.skip_frames.clear();
  for (int slot : s.skipped) {
    const double end = p.slots.slots[static_cast<size_t>(slot)].last;
    const double* at = std::lower_bound(s.u.data(), s.u.data() + s.u.size(), end - 1e-9);
    s.skip_frames.push_back(at - s.u.data());
  }
  // Each take's frame at each output frame: the residual's poses and the foot lock's drift read
  // it; written again only when a loop cuts the output.
  write_sources(p, s.sampler, st.first, sources);
  if (keyed) weights_over_frames(keys, s.u.size(), p.fps, s.frame_w);
  return finish;
}

void mix_root(const PreparedTakes& p, const WeightKeys& keys, const std::vector<double>& root_w, double root_pull_seconds,
              const PathLeash& leash, const PlayedStretch& st, MixedTrajectory& s) {
  const int n = p.size();
  const bool keyed = !keys.empty();
  const Eigen::Index first = st.first, length = st.length();
  if (keyed) {  // each sample with its own weights
    s.steps.setZero(length, 3);
    s.target.setZero(length, 2);
    s.contacts_u.setZero(length, 2);
    for (int i = 0; i < n; ++i) {
      const auto w = s.sample_w.col(i).asDiagonal();
      s.steps += w * p.takes[i].steps.middleRows(first, length);
      s.target += w * p.takes[i].ground.middleRows(first, length);
      s.contacts_u += w * p.takes[i].contacts.middleRows(first, length);
    }
  } else {
    weighted_columns(p, root_w, &PreparedTake::steps, first, length, s.terms, s.steps);
    weighted_columns(p, root_w, &PreparedTake::ground, first, length, s.terms, s.target);
    weighted_columns(p, root_w, &PreparedTake::contacts, first, length, s.terms, s.contacts_u);
  }
  // A slot left out takes no step (its whole turns, spread, are still taken); the turn its steps
  // would have taken turns the weighted paths after it back.
  s.skip_turns.clear();
  for (int slot : s.skipped) {
    const Eigen::Index a = p.slots.slots[static_cast<size_t>(slot)].first - first, b = p.slots.slots[static_cast<size_t>(slot)].last - first;
    const bool inside = a >= 0 && b < length && b > a;
    s.skip_turns.push_back(inside ? s.steps.col(2).segment(a, b - a).sum() : 0.0);
    if (inside) s.steps.middleRows(a, b - a).setZero();
  }
  for (int i = 1; i < n; ++i) {
    s.flips = p.takes[i].turn_flips.segment(first, length);
    if (keyed) add_spread_turns(s.flips, s.sample_w.col(i), p.fps, s.steps);
    else add_spread_turns(s.flips, root_w[i], p.fps, s.steps);
  }
  // The pull keeps a mix among its takes' paths (a warp matches steps, not turns, so integrated
  // steps alone drift away from every take). With a negative weight (a transfer's on its neutral
  // take, an exaggeration) there is no path among them to keep to: the weighted paths are a path
  // no take walks (content + style - neutral, each registered path with its own drift), and the
  // planted feet would slide to follow it. Such a mix integrates its steps alone.
  bool convex = true;
  for (int i = 0; i < n; ++i) {
    convex &= root_w[i] >= 0.0;
    for (const WeightKey& key : keys) convex &= key.weights[static_cast<size_t>(i)] >= 0.0;
  }
  const bool leashed = leash.body_heights > 0.0;
  if (leashed) {
    s.path_u = p.takes.front().ground.middleRows(first, length);
    s.path_heading_u = p.reference_heading.segment(first, length);
  }
  // The slots the clock leaves out: the root is made on the samples played alone (the paths it
  // is pulled towards or kept near closed up over them, moved rigidly), so that neither the
  // pull nor the leash's windows see the samples no output frame shows, and spread back after.
  const bool skips = !s.skipped.empty();
  if (skips) {
    played_rows(p.slots, s.skipped, first, length, s.kept);
    close_skipped(p.slots, s.skipped, static_cast<int>(first), s.target, nullptr, &s.skip_turns);
    if (leashed) close_skipped(p.slots, s.skipped, static_cast<int>(first), s.path_u, &s.path_heading_u);
    summed_steps(s.steps, s.kept, s.played_steps);
    s.steps.swap(s.played_steps);
    keep_rows(s.target, s.kept, s.played_steps);
    s.target.swap(s.played_steps);
    if (leashed) {
      keep_rows(s.path_u, s.kept, s.played_steps);
      s.path_u.swap(s.played_steps);
      keep_rows(s.path_heading_u, s.kept, s.played_heading);
      s.path_heading_u.swap(s.played_heading);
    }
  }
  integrate_root_towards(s.steps, s.target, p.reference_heading[first], p.fps, convex ? root_pull_seconds : 0.0,
                         &s.ground_u, &s.heading_u);
  if (leashed) {
    s.free_ground_u = s.ground_u;
    s.free_heading_u = s.heading_u;
    remove_path_drift(s.ground_u, s.path_u, static_cast<Eigen::Index>(std::lround(leash.drift_seconds * p.fps)), s.drift_u);
    keep_near_path(s.ground_u, s.path_u, leash.body_heights * p.feet.body_height);
    keep_near_heading(s.heading_u, s.path_heading_u, kPathLeashHeading);
    // A loop of a reference that does not walk (a stance, a repeated gesture) travels as the
    // reference does over the loop: any other travel is a gap between its last frame and its
    // first's next repeat, which the foot lock's seam then spreads over feet that never swing
    // (they crept as far as the root had drifted under a style that sways its hips). A walking
    // loop's travel is its strides', which the stride map fits and the seam takes up over the swings.
    if (p.reference().cycles.kind != CycleKind::kGait && shows_whole_loop(p, st.first, st.last)) {
      // Over the loop's samples: its last frame is where the clock ends (output_clock).
      Eigen::Index end = std::lround(s.u[s.u.size() - 1]) - first;
      if (skips) end = std::upper_bound(s.kept.begin(), s.kept.end(), end) - s.kept.begin() - 1;
      keep_loop_travel(s.ground_u, s.path_u, end);
    }
    // A content that does not walk (no gait cycles: a jump, a stand) has no stride to fit.
    if (p.reference().cycles.kind == CycleKind::kGait)
      stride_map(s.free_ground_u, s.free_heading_u, s.ground_u, s.heading_u, p.fps, p.feet.body_height, s.stride_u);
    else
      s.stride_u.resize(0, 4);
  } else {
    s.stride_u.resize(0, 4);
  }
  if (skips) {
    spread_rows(s.ground_u, s.kept, length, s.played_steps);
    s.ground_u.swap(s.played_steps);
    spread_rows(s.heading_u, s.kept, length, s.played_heading);
    s.heading_u.swap(s.played_heading);
    if (s.stride_u.rows() > 0) {
      spread_rows(s.stride_u, s.kept, length, s.played_steps);
      s.stride_u.swap(s.played_steps);
    }
  }
  s.contacts_u = (s.contacts_u.array() > 0.5).cast<double>();
}

void write_sources(const PreparedTakes& p, const RowSampler& at, int first, Eigen::MatrixXd& sources) {
  const Eigen::Index frames = at.row.size();
  sources.resize(frames, p.size());
  for (int i = 0; i < p.size(); ++i) {
    const Eigen::VectorXd& f = p.timeline.frames[i];
    for (Eigen::Index k = 0; k < frames; ++k) {
      const Eigen::Index r = first + at.row[k];
      sources(k, i) = r + 1 < f.size() ? (1 - at.frac[k]) * f[r] + at.frac[k] * f[r + 1] : f[r];
    }
  }
}

}  // namespace mostyle
