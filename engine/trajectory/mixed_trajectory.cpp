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

// The ground path's travel from its first sample to its last made the path's own (x, z), the
// difference taken away in even shares along it. ground, path: U x 2. O(U).
void keep_loop_travel(Eigen::MatrixXd& ground, const Eigen::Ref<const Eigen::MatrixXd>& path) {
  const Eigen::Index n = ground.rows();
  if (n < 2 || path.rows() != n) return;
  const Eigen::RowVector2d off =
      (ground.row(n - 1) - ground.row(0)) - (path.row(n - 1) - path.row(0));
  for (Eigen::Index k = 1; k < n; ++k) ground.row(k) -= (double(k) / double(n - 1)) * off;
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
  double clock_at_last = 0.0;
  if (keyed && !weights.reference_timing) {
    mixed_timeline(p.timeline, keys, p.fps, {st.first, st.last}, s.u, &s.sample_w, &clock_at_last);
  } else {
    mixed_timeline(p.timeline, timing, {st.first, st.last}, s.u, &clock_at_last);
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
    land_on_last(s.u, st.last, clock_at_last);
    finish.loop = false;
  }
  s.u_stretch = s.u.array() - double(st.first);
  s.sampler.set(s.u_stretch, st.length());
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
  integrate_root_towards(s.steps, s.target, p.reference_heading[first], p.fps, convex ? root_pull_seconds : 0.0,
                         &s.ground_u, &s.heading_u);
  if (leash.body_heights > 0.0) {
    s.free_ground_u = s.ground_u;
    s.free_heading_u = s.heading_u;
    remove_path_drift(s.ground_u, p.takes.front().ground.middleRows(first, length),
                      static_cast<Eigen::Index>(std::lround(leash.drift_seconds * p.fps)), s.drift_u);
    keep_near_path(s.ground_u, p.takes.front().ground.middleRows(first, length), leash.body_heights * p.feet.body_height);
    keep_near_heading(s.heading_u, p.reference_heading.segment(first, length), kPathLeashHeading);
    // A loop of a reference that does not walk (a stance, a repeated gesture) travels as the
    // reference does over the loop: any other travel is a gap between its last frame and its
    // first's next repeat, which the foot lock's seam then spreads over feet that never swing
    // (they crept as far as the root had drifted under a style that sways its hips). A walking
    // loop's travel is its strides', which the stride map fits and the seam takes up over the swings.
    if (p.reference().cycles.kind != CycleKind::kGait && shows_whole_loop(p, st.first, st.last))
      keep_loop_travel(s.ground_u, p.takes.front().ground.middleRows(first, length));
    // A content that does not walk (no gait cycles: a jump, a stand) has no stride to fit.
    if (p.reference().cycles.kind == CycleKind::kGait)
      stride_map(s.free_ground_u, s.free_heading_u, s.ground_u, s.heading_u, p.fps, p.feet.body_height, s.stride_u);
    else
      s.stride_u.resize(0, 4);
  } else {
    s.stride_u.resize(0, 4);
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
