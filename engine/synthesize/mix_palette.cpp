#include "engine/synthesize/mix_palette.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include <Eigen/QR>

#include "engine/base/clock.h"
#include "engine/base/error.h"
#include "engine/base/weighted_sum.h"
#include "engine/post/stride_warp.h"
#include "engine/prepare/major_skeleton.h"
#include "engine/synthesize/synthesis.h"

namespace mostyle {
namespace {

using Clock = std::chrono::steady_clock;
// A bone a mix leaves shorter than this fraction of its length (the takes' limbs pointing apart)
// turns towards its own direction gradually (limb_length.h LimbLengthOptions::short_fraction); a
// lower fraction lets a short bone, a wrist, spin round in a few frames.
// Test: "a short bone leans on its previous direction instead of spinning round" (tests/engine/kinematics/limb_length_test.cpp).
constexpr double kShortBoneFraction = 0.75;
constexpr double kWeightSumTolerance = 1e-6;

// A fractional row, clamped to [0, rows - 1]: the row before it and how far towards the next.
struct RowAt {
  Eigen::Index r = 0, next = 0;
  double f = 0.0;
  RowAt(double at, Eigen::Index rows) {
    const Eigen::Index last = rows - 1;
    const double c = std::clamp(at, 0.0, double(last));
    r = std::min<Eigen::Index>(static_cast<Eigen::Index>(c), std::max<Eigen::Index>(last - 1, 0));
    next = std::min(r + 1, last);
    f = last == 0 ? 0.0 : c - double(r);
  }
  template <typename X>
  double of(const X& x, Eigen::Index column) const {
    return (1.0 - f) * x(r, column) + f * x(next, column);
  }
};

// How far each planted foot joint moves from output frame k to k + 1 in the body's frame, as the
// takes mixed move theirs while planted at the frames shown (PreparedTake::foot_travel), weighted
// as the poses are (a transfer's content + style - neutral too; the lock allows no more than the
// output's own foot moves) (K x 2 kFootJoints, x and z per joint; the last row 0): what the foot
// lock lets the output's planted feet do. A take whose foot is in the air there adds nothing.
// O(K x N), no allocation once `out` is sized.
void planted_drift(const PreparedTakes& p, const Eigen::MatrixXd& sources, const std::vector<double>& weights,
                   const Eigen::MatrixXd* frame_w, Eigen::MatrixXd& out) {
  const Eigen::Index frames = sources.rows();
  out.setZero(frames, 2 * kFootJoints);
  for (int i = 0; i < p.size(); ++i) {
    const Eigen::MatrixXd& travel = p.takes[static_cast<size_t>(i)].foot_travel;
    const Eigen::Index rows = travel.rows();
    if (frame_w == nullptr && weights[static_cast<size_t>(i)] == 0.0) continue;
    // Frame k + 1's travel read once, as frame k's on the next step.
    double at[2 * kFootJoints], next[2 * kFootJoints];
    const auto read = [&](Eigen::Index k, double* values) {
      const RowAt r(sources(k, i), rows);
      for (Eigen::Index c = 0; c < 2 * kFootJoints; ++c) values[c] = r.of(travel, c);
    };
    if (frames > 0) read(0, at);
    for (Eigen::Index k = 0; k + 1 < frames; ++k) {
      read(k + 1, next);
      const double w = frame_w != nullptr ? (*frame_w)(k, i) : weights[static_cast<size_t>(i)];
      if (w != 0.0)
        for (Eigen::Index c = 0; c < 2 * kFootJoints; ++c) out(k, c) += w * (next[c] - at[c]);
      std::copy(next, next + 2 * kFootJoints, at);
    }
  }
}

// K x kFootJoints: how high the takes mixed hold each foot joint at output frame k, in planted
// bands (kPlantedHeightFraction of the body's height) above its floor, mixed with the weights the
// planted drift takes. Each take's joint at the frame shown (PreparedTake::foot_height, linear
// between frames, as the output's poses are read)
// over its floor as planted_feet.h takes it, a low percentile of its heights, but over the frames
// shown: an output that shows part of a take has the floor of that part, and the take's heights
// are read against the same. O(K x N), no allocation once `out` and `scratch` are sized.
void feet_heights(const PreparedTakes& p, const Eigen::MatrixXd& sources, const std::vector<double>& weights,
                  const Eigen::MatrixXd* frame_w, Eigen::MatrixXd& out, std::vector<double>& scratch) {
  const Eigen::Index frames = sources.rows();
  out.setZero(frames, kFootJoints);
  if (frames == 0) return;
  const double band = kPlantedHeightFraction * p.feet.body_height;
  const size_t k_floor = static_cast<size_t>(kPlantedFloorPercentile * static_cast<double>(frames - 1));
  for (int i = 0; i < p.size(); ++i) {
    const Eigen::MatrixXd& height = p.takes[static_cast<size_t>(i)].foot_height;
    if (height.rows() == 0 || (frame_w == nullptr && weights[static_cast<size_t>(i)] == 0.0)) continue;
    for (int j = 0; j < kFootJoints; ++j) {
      scratch.resize(2 * static_cast<size_t>(frames));
      for (Eigen::Index k = 0; k < frames; ++k)
        scratch[static_cast<size_t>(frames + k)] = scratch[static_cast<size_t>(k)] =
            RowAt(sources(k, i), height.rows()).of(height, j);
      std::nth_element(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(k_floor),
                       scratch.begin() + frames);
      const double floor = scratch[k_floor];
      for (Eigen::Index k = 0; k < frames; ++k) {
        const double w = frame_w != nullptr ? (*frame_w)(k, i) : weights[static_cast<size_t>(i)];
        if (w != 0.0) out(k, j) += w * (scratch[static_cast<size_t>(frames + k)] - floor) / band;
      }
    }
  }
}

// MixResult::foot_sliding_inputs: weights, one per take, or with keys each take's mean over the
// output frames (frame_w, K x N); the reference's own when of_reference (a transfer). O(K x N).
double inputs_planted_speed(const PreparedTakes& p, const std::vector<double>& weights, const Eigen::MatrixXd* frame_w,
                            bool of_reference) {
  if (of_reference) return p.takes.front().planted.speed;
  double sum = 0.0;
  for (int i = 0; i < p.size(); ++i) {
    const double w = frame_w != nullptr && frame_w->rows() > 0 ? frame_w->col(i).mean() : weights[static_cast<size_t>(i)];
    if (w < 0.0 || (frame_w != nullptr && frame_w->rows() > 0 && frame_w->col(i).minCoeff() < 0.0))
      return p.takes.front().planted.speed;
    sum += w * p.takes[static_cast<size_t>(i)].planted.speed;
  }
  return sum;
}

}  // namespace

std::vector<double> normalized_weights(const std::vector<double>& typed) {
  double sum = 0.0;
  for (double w : typed) sum += w;
  if (std::abs(sum - 1.0) > kTypedWeightSumTolerance || sum == 1.0) return typed;
  std::vector<double> out = typed;
  for (double& w : out) w /= sum;
  return out;
}

namespace {

// Throws InputError on a layer of a take that is not one of `takes`, or weights per component
// that are not `components`: what take_weights and take_component_weights read.
void check_layers(const MixLayers& layers, int takes, int components) {
  auto check_take = [&](int take) {
    if (take < 0 || take >= takes)
      throw InputError("expected layers of takes 1 to " + std::to_string(takes) + ", found one of take " +
                       std::to_string(take + 1));
  };
  auto check_components = [&](const std::vector<double>& w) {
    if (!w.empty() && static_cast<int>(w.size()) != components)
      throw InputError("expected per-component weights of " + std::to_string(components) + " components x " +
                       std::to_string(takes) + " takes");
  };
  for (const MixLayer& l : layers.layers) {
    check_take(l.take);
    check_components(l.component_weights);
  }
  for (const AdditiveLayer& l : layers.additive) {
    check_take(l.take);
    check_take(l.from);
    check_components(l.component_weights);
  }
}

// Throws InputError on each take's weights (`weights`, and per component `part_w`, from the
// layers) or the keys outside what `params` allows: finite, within its range, summing to 1.
void check_weights(const MixParams& params, const std::vector<double>& weights, const Eigen::MatrixXd& part_w) {
  const int takes = static_cast<int>(weights.size());
  auto check_row = [&](auto weight_of, const std::string& what) {
    double sum = 0.0;
    for (int i = 0; i < takes; ++i) {
      const double w = weight_of(i);
      if (!std::isfinite(w)) throw InputError("expected finite " + what);
      if (w < params.min_weight - 1e-12 || w > params.max_weight + 1e-12)
        throw InputError("expected " + what + " from " + std::to_string(params.min_weight).substr(0, 5) + " to " +
                         std::to_string(params.max_weight).substr(0, 4) + ", found " + std::to_string(w) +
                         " for take " + std::to_string(i + 1));
      sum += w;
    }
    if (std::abs(sum - 1.0) > kWeightSumTolerance)
      throw InputError("expected " + what + " that sum to 1, found a sum of " + std::to_string(sum));
  };
  check_row([&](int i) { return weights[static_cast<size_t>(i)]; }, "weights");
  if (!params.keys.empty()) {
    validate_keys(params.keys, takes);
    for (size_t k = 0; k < params.keys.size(); ++k)
      check_row([&](int i) { return params.keys[k].weights[static_cast<size_t>(i)]; },
                "key " + std::to_string(k + 1) + "'s weights");
    if (part_w.size() > 0)
      throw InputError("weights keyed in time mix one weight per take for the whole body; give per-part weights "
                       "without keys, or keys without per-part weights");
    if (params.finish.loop)
      throw InputError("a loop repeats one stretch with one set of weights; keys change the weights over time: "
                       "give keys or a loop, not both");
  }
  for (Eigen::Index c = 0; c < part_w.rows(); ++c) check_row([&](int i) { return part_w(c, i); }, "part weights");
}

}  // namespace

void MixParams::Validate(int takes, int components) const {
  check_layers(layers, takes, components);
  std::vector<double> weights;
  Eigen::MatrixXd part_w;
  take_weights(layers, takes, weights);
  take_component_weights(layers, takes, components, part_w);
  check_weights(*this, weights, part_w);
}

namespace {

// Each take's weights from the layers (s.weights, s.part_w), or InputError where a mix cannot
// run: params.Validate, and paper mode with more than two takes, weights per part or keys.
void resolve_and_check_mix(const PreparedTakes& p, const Decomposed& d, const MixParams& params, MixScratch& s) {
  const int n = p.size();
  check_layers(params.layers, n, d.components());
  take_weights(params.layers, n, s.weights);
  take_component_weights(params.layers, n, d.components(), s.part_w);
  check_weights(params, s.weights, s.part_w);
  if (d.paper() != nullptr && (n != 2 || s.part_w.size() > 0))
    throw InputError("paper mode blends two takes with one weight; mix several takes, or weights per body part, in "
                     "shared mode");
  if (d.paper() != nullptr && !params.keys.empty())
    throw InputError("paper mode blends with one alpha for the whole take; key the weights in time in shared mode");
}

// Whether the per-component weights differ from the overall weights anywhere (per-component
// weights that are all the overall weights are the plain mix). Sets s.overall, the body's
// overall weights (each take's mean over the components when they differ per part), which mix
// the root, the contacts and, unless the reference's is kept, the timing (s.timing).
bool mix_overall_weights(const MixParams& params, int n, MixScratch& s) {
  bool per_component = false;
  for (Eigen::Index c = 0; c < s.part_w.rows(); ++c)
    for (int i = 0; i < n; ++i) per_component |= s.part_w(c, i) != s.weights[i];
  s.overall = s.weights;
  if (per_component)
    for (int i = 0; i < n; ++i) s.overall[i] = s.part_w.col(i).mean();
  s.timing.assign(n, 0.0);
  if (params.reference_timing) s.timing[0] = 1.0;
  else s.timing = s.overall;
  return per_component;
}

// The paper's synthesis (3.6) on the samples with alpha the second take's weight: A's weights on
// a blend of the takes' cores, or B's basic-motion core at one level (3.5; the chain sums back to
// X with A's residual). No residuals otherwise, as the paper has it.
void paper_poses(const PreparedTakes& p, const Decomposed& d, const MixParams& params, const PlayedStretch& st,
                 MixScratch& s, Eigen::MatrixXd& local) {
  const PaperComponents* paper = d.paper();
  const double alpha = s.weights[1];
  if (d.params.basic_motions > 0) {
    synthesize_basic_motions(paper->basic_synthesis, params.swap_level, alpha, s.x);
    s.x += paper->basic_a.residual;
  } else {
    synthesize_paper(paper->synthesis, alpha, s.x);
  }
  s.samples.resize(s.x.rows(), s.x.cols());
  s.samples.noalias() = s.x * p.scale;
  s.samples.rowwise() += s.weights[0] * p.takes[0].mean + alpha * p.takes[1].mean;
  s.stretch = s.samples.middleRows(st.first, st.length());
  s.trajectory.sampler.apply(s.stretch, local);
}

// sum_i w_i (W_i C scale + mean_i + residual_i) at the output frames only: each take's own pose,
// read straight at the frame the output frame shows (one-hot weights give the take's own
// frames), one output frame at a time over the takes' transposed poses (a frame is a contiguous
// column): the two frames of each take around it, weighted, summed in one pass.
void own_poses(const PreparedTakes& p, const MixParams& params, const Eigen::MatrixXd& sources, MixScratch& s,
               Eigen::MatrixXd& local) {
  const bool keyed = !params.keys.empty();
  const Eigen::Index channels = p.takes.front().own_local_t.rows();
  const Eigen::Index frames = sources.rows();
  // A block of output frames at a time, turned into local's rows while it is still in the cache.
  constexpr Eigen::Index kBlock = 64;
  s.local_t.resize(channels, std::min(kBlock, frames));
  local.resize(frames, channels);
  s.terms.resize(2 * static_cast<size_t>(p.size()));
  for (Eigen::Index k0 = 0; k0 < frames; k0 += kBlock) {
    const Eigen::Index n = std::min(kBlock, frames - k0);
    for (Eigen::Index b = 0; b < n; ++b) {
      const Eigen::Index k = k0 + b;
      int count = 0;
      for (int i = 0; i < p.size(); ++i) {
        const double w = keyed ? s.trajectory.frame_w(k, i) : s.weights[i];
        if (w == 0.0) continue;
        const Eigen::MatrixXd& x = p.takes[i].own_local_t;
        const RowAt at(sources(k, i), x.cols());
        s.terms[count++] = {w * (1.0 - at.f), x.col(at.r).data()};
        if (at.f != 0.0) s.terms[count++] = {w * at.f, x.col(at.next).data()};
      }
      weighted_sum(s.terms.data(), count, channels, s.local_t.col(b).data());
    }
    local.middleRows(k0, n) = s.local_t.leftCols(n).transpose();
  }
}

// Per joint (three channels of a take's own poses, 3M x F), the RMS distance of its positions
// from their mean over the take's frames: how much the take moves it. Two passes over the frames,
// a contiguous column each; mean and spread: per channel scratch. No allocation once sized.
void joint_amplitudes(const Eigen::MatrixXd& x_t, Eigen::VectorXd& mean, Eigen::VectorXd& spread, Eigen::VectorXd& amp) {
  const Eigen::Index frames = x_t.cols();
  mean.setZero(x_t.rows());
  spread.setZero(x_t.rows());
  for (Eigen::Index f = 0; f < frames; ++f) mean += x_t.col(f);
  mean /= double(std::max<Eigen::Index>(1, frames));
  for (Eigen::Index f = 0; f < frames; ++f) spread += (x_t.col(f) - mean).cwiseAbs2();
  amp.resize(x_t.rows() / 3);
  for (Eigen::Index j = 0; j < amp.size(); ++j)
    amp[j] = std::sqrt(spread.segment(3 * j, 3).sum() / double(std::max<Eigen::Index>(1, frames)));
}

// A style's change from a neutral of another action (both aligned to the content by their
// structure, not phase by phase as cycles are): how the style moves a joint differently from the
// neutral, about the change's mean, belongs to that action's strokes (one wave's arm against
// another's). Put on a content that holds the joint still (a raised right hand styled from a
// left-hand wave's takes), it would set a still arm moving, none of the content's. Per joint it
// keeps that movement as far as the content moves the joint against the neutral (the content's
// movement over the neutral's, at most 1) and leaves the rest out; the change's mean, the
// style's posture, stays whole. O(K x 3M) per such layer; no allocation once scratch is sized.
void still_where_content_is(const PreparedTakes& p, const MixParams& params, const Eigen::MatrixXd& sources,
                            MixScratch& s, Eigen::MatrixXd& local) {
  const bool keyed = !params.keys.empty();
  const Eigen::Index frames = local.rows(), channels = local.cols(), joints = channels / 3;
  if (frames == 0) return;
  for (const AdditiveLayer& l : params.layers.additive) {
    if (l.take == l.from || l.from == 0 || (!keyed && l.weight == 0.0)) continue;
    const PreparedTake& take = p.takes[static_cast<size_t>(l.take)];
    const PreparedTake& from = p.takes[static_cast<size_t>(l.from)];
    if (!take.registration.empty() || !from.registration.empty()) continue;
    joint_amplitudes(p.reference().own_local_t, s.channel_mean, s.channel_spread, s.amp_content);
    joint_amplitudes(from.own_local_t, s.channel_mean, s.channel_spread, s.amp_from);
    s.left_out.resize(joints);
    bool any = false;
    for (Eigen::Index j = 0; j < joints; ++j) {
      const double kept = s.amp_from[j] > 0.0 ? std::min(1.0, s.amp_content[j] / s.amp_from[j]) : 1.0;
      s.left_out[j] = 1.0 - kept;
      any |= s.left_out[j] > 0.0;
    }
    if (!any) continue;
    const Eigen::MatrixXd& xt = take.own_local_t;
    const Eigen::MatrixXd& xf = from.own_local_t;
    s.change.resize(frames, channels);
    for (Eigen::Index k = 0; k < frames; ++k) {
      const RowAt a(sources(k, l.take), xt.cols()), b(sources(k, l.from), xf.cols());
      s.change.row(k) = ((1.0 - a.f) * xt.col(a.r) + a.f * xt.col(a.next) - (1.0 - b.f) * xf.col(b.r) -
                         b.f * xf.col(b.next)).transpose();
    }
    s.change_mean = s.change.colwise().mean();
    for (Eigen::Index c = 0; c < channels; ++c) {
      const double out = s.left_out[c / 3];
      if (out == 0.0) continue;
      for (Eigen::Index k = 0; k < frames; ++k) {
        const double w = keyed ? s.trajectory.frame_w(k, l.take) : l.weight;
        local(k, c) -= w * out * (s.change(k, c) - s.change_mean[c]);
      }
    }
  }
}

// sum_i w_i (W_i C scale + mean_i) at the output frames: each take's reconstruction without its
// residual, with keys each output frame with its own weights.
void reconstructed_poses(const PreparedTakes& p, const SharedComponents& shared, const MixParams& params,
                         const PlayedStretch& st, MixScratch& s, Eigen::MatrixXd& local) {
  const bool keyed = !params.keys.empty();
  for (int i = 0; i < p.size(); ++i) {
    s.stretch = shared.reconstructed[i].middleRows(st.first, st.length());
    if (keyed) {
      s.trajectory.sampler.apply(s.stretch, s.samples);
      if (i == 0) local = s.trajectory.frame_w.col(0).asDiagonal() * s.samples;
      else local += s.trajectory.frame_w.col(i).asDiagonal() * s.samples;
    } else if (i == 0) {
      s.trajectory.sampler.apply(s.stretch, local);
      local *= s.weights[0];
    } else {
      s.trajectory.sampler.accumulate(s.stretch, s.weights[i], local);
    }
  }
}

// Each component's weight column mixed per take, each joint's mean and residual with its
// components' mean weights (body_parts.h joint_values).
void part_poses(const PreparedTakes& p, const Decomposed& d, const MixParams& params, const PlayedStretch& st,
                MixScratch& s, Eigen::MatrixXd& local) {
  const SharedComponents* shared = d.shared();
  const int n = p.size();
  s.joint_weights = joint_values(d.support, s.part_w);
  s.component_w.setZero(st.length(), d.components());
  for (int i = 0; i < n; ++i)
    s.component_w +=
        shared->stacked.weights[i].middleRows(st.first, st.length()) * s.part_w.col(i).asDiagonal();
  s.samples.noalias() = s.component_w * shared->stacked.components * p.scale;
  // Each take's joint weights spread over the joint's three channels: the means in one row, the
  // residuals a whole-matrix pass per take.
  s.mixed_mean.setZero(s.samples.cols());
  for (int i = 0; i < n; ++i) {
    s.channel_w.resize(s.samples.cols());
    for (Eigen::Index j = 0; j < s.joint_weights.rows(); ++j) s.channel_w.segment(3 * j, 3).setConstant(s.joint_weights(j, i));
    s.mixed_mean += s.channel_w.cwiseProduct(p.takes[i].mean);
    if (params.residual) s.samples += shared->residual[i].middleRows(st.first, st.length()) * s.channel_w.asDiagonal();
  }
  s.samples.rowwise() += s.mixed_mean;
  s.trajectory.sampler.apply(s.samples, local);
}

// Where the clock leaves a cycle slot out (s.trajectory.skipped), the output's pose would jump
// from the slot's first sample to its last (each take's pose there differs by a cycle's
// variation: a replayed cycle's seam, a stride longer than the last): the jump, mixed as the poses
// are (the overall weights; with keys, those at the frame after it; per part, each joint's), is taken away at the frame
// after it and eased back in over the next cycle, so the poses go on from where they were and are
// the takes' own again a cycle on. O(skipped x (N + cycle) x 3M).
void ease_skipped_slots(const PreparedTakes& p, const MixParams& params, bool per_component, MixScratch& s,
                        Eigen::MatrixXd& local, MixResult& out) {
  const MixedTrajectory& t = s.trajectory;
  out.slot_skips.clear();
  const Eigen::Index ease = std::max<Eigen::Index>(1, std::lround(p.reference().timeline_cycles().period));
  out.slot_ease = ease;
  if (t.skipped.empty()) return;
  const bool keyed = !params.keys.empty();
  const Eigen::Index frames = local.rows();
  for (size_t j = 0; j < t.skipped.size(); ++j) {
    const Eigen::Index k = t.skip_frames[j];
    if (k <= 0 || k >= frames) continue;
    if (out.slot_skips.empty() || out.slot_skips.back() != k) out.slot_skips.push_back(k);
    const CycleSlots::Slot& slot = p.slots.slots[static_cast<size_t>(t.skipped[j])];
    s.mixed_mean.setZero(local.cols());
    for (int i = 0; i < p.size(); ++i) {
      const auto jump = p.takes[i].local.row(slot.last) - p.takes[i].local.row(slot.first);
      if (per_component) {  // each joint's jump as its poses are mixed (part_poses' joint weights)
        for (Eigen::Index j = 0; j < s.joint_weights.rows(); ++j)
          s.mixed_mean.segment(3 * j, 3) += s.joint_weights(j, i) * jump.segment(3 * j, 3);
        continue;
      }
      const double w = keyed ? t.frame_w(k, i) : s.overall[static_cast<size_t>(i)];
      if (w != 0.0) s.mixed_mean += w * jump;
    }
    for (Eigen::Index f = k; f < std::min(frames, k + ease); ++f)
      local.row(f) -= (1.0 - double(f - k) / double(ease)) * s.mixed_mean;
  }
}

// The rig the clean-up measures the output with: the reference's, the foot lock held to the
// takes' fastest joint and planted feet (MixResult::foot_sliding_inputs).
FinishRig mix_rig(const PreparedTakes& p, double fastest, double planted_speed) {
  FinishRig rig;
  rig.parents = &p.parents;
  rig.lengths = &p.lengths;
  rig.feet = &p.feet;
  rig.short_bone_fraction = kShortBoneFraction;
  rig.lock_limits.fastest_joint = fastest;
  rig.lock_limits.planted_speed = planted_speed;
  return rig;
}

// The clean-up's first part (finish_preview): the output in the world, its limb lengths; where a
// loop cut the output, the sources of the loop's frames (the frames before the cut kept in
// s.sources_uncut for the planted drift). Leaves s.pending for finish_rest_of_mix.
void preview_finish(const PreparedTakes& p, const MixParams& params, const PlayedStretch& st,
                    const FinishOptions& finish, MixScratch& s, MixResult& out) {
  const bool keyed = !params.keys.empty();
  out.foot_sliding_inputs = inputs_planted_speed(p, s.overall, keyed ? &s.trajectory.frame_w : nullptr, params.feet_of_reference);
  out.fastest_inputs = st.fastest;
  const FinishRig rig = mix_rig(p, st.fastest, out.foot_sliding_inputs);
  FinishPath path;
  path.sampler = &s.trajectory.sampler;
  path.ground_u = &s.trajectory.ground_u;
  path.heading_u = &s.trajectory.heading_u;
  path.contacts_u = &s.trajectory.contacts_u;
  finish_preview(path, rig, finish, out.local, s.trajectory.u_stretch, s.finish, out.motion);
  if (finish.loop || finish.closed) {  // the loop's frames only
    s.sources_uncut = out.sources;
    s.trajectory.sampler.set(s.trajectory.u_stretch, st.length());
    write_sources(p, s.trajectory.sampler, st.first, out.sources);
  }
  s.pending.waiting = true;
  s.pending.options = finish;
  s.pending.fastest = st.fastest;
}

// The rest of the clean-up (finish_rest) after preview_finish: with a foot lock the takes'
// planted drift (s.drift), then the speed limit, the lock and the measures.
void finish_rest_of_mix(const PreparedTakes& p, const MixParams& params, MixScratch& s, MixResult& out) {
  const int n = p.size();
  const bool keyed = !params.keys.empty();
  const FinishOptions& finish = s.pending.options;
  const FinishRig rig = mix_rig(p, s.pending.fastest, out.foot_sliding_inputs);
  const Eigen::MatrixXd& sources = finish.loop || finish.closed ? s.sources_uncut : out.sources;
  const Eigen::MatrixXd* drift = nullptr;
  const Eigen::MatrixXd* feet_height = nullptr;
  if (finish.foot_lock) {
    if (params.feet_of_reference) {  // the reference's own planted moves and feet alone
      s.drift_w.assign(static_cast<size_t>(n), 0.0);
      s.drift_w.front() = 1.0;
      planted_drift(p, sources, s.drift_w, nullptr, s.drift);
      feet_heights(p, sources, s.drift_w, nullptr, s.feet_height, s.heights);
    } else {
      planted_drift(p, sources, s.overall, keyed ? &s.trajectory.frame_w : nullptr, s.drift);
      feet_heights(p, sources, s.overall, keyed ? &s.trajectory.frame_w : nullptr, s.feet_height, s.heights);
    }
    // No planted move across a slot left out: the takes' travel over it is not played.
    for (Eigen::Index k : s.trajectory.skip_frames)
      if (k >= 1 && k - 1 < s.drift.rows()) s.drift.row(k - 1).setZero();
    drift = &s.drift;
    feet_height = &s.feet_height;
  }
  finish_rest(rig, finish, s.finish, out.motion, drift, feet_height);
  s.pending.waiting = false;
}

}  // namespace

void mix_palette(const PreparedTakes& p, const Decomposed& d, const MixParams& params, MixScratch& s,
                 MixResult& out, StageTimes* times) {
  resolve_and_check_mix(p, d, params, s);
  s.pending.waiting = false;
  const auto t0 = Clock::now();
  const bool per_component = mix_overall_weights(params, p.size(), s);
  const PlayedStretch st = played_stretch(p, s.weights, params.keys, s.part_w, per_component, s.timing);
  out.first_sample = st.first;
  out.last_sample = st.last;
  ClockWeights clock;
  clock.keys = &params.keys;
  clock.timing = &s.timing;
  clock.reference_timing = params.reference_timing;
  clock.reference_cycles = params.reference_cycles;
  const FinishOptions finish = output_clock(p, clock, params.finish, st, s.trajectory, out.sources);
  if (d.paper() != nullptr) paper_poses(p, d, params, st, s, out.local);
  else if (per_component) part_poses(p, d, params, st, s, out.local);
  else if (params.residual) own_poses(p, params, out.sources, s, out.local);
  else reconstructed_poses(p, *d.shared(), params, st, s, out.local);
  if (d.paper() == nullptr) still_where_content_is(p, params, out.sources, s, out.local);
  ease_skipped_slots(p, params, per_component, s, out.local, out);
  if (times != nullptr) times->synthesize_ms = ms_since(t0);

  const auto t1 = Clock::now();
  mix_root(p, params.keys, s.overall, params.root_pull_seconds, params.path_leash, st, s.trajectory);
  if (s.trajectory.stride_u.rows() > 0) {  // a root on a leash: the strides fitted to its pace
    s.trajectory.sampler.apply(s.trajectory.stride_u, s.stride);
    warp_strides(out.local, s.stride, p.feet);
  }
  preview_finish(p, params, st, finish, s, out);
  out.sample = s.trajectory.u_stretch.array() + double(st.first);
  if (!params.preview) finish_rest_of_mix(p, params, s, out);
  if (times != nullptr) times->postprocess_ms = ms_since(t1);
}

void finish_mix_palette(const PreparedTakes& p, const MixParams& params, MixScratch& s, MixResult& out,
                        StageTimes* times) {
  if (!s.pending.waiting) return;
  const auto t0 = Clock::now();
  finish_rest_of_mix(p, params, s, out);
  if (times != nullptr) times->postprocess_ms += ms_since(t0);
}

Eigen::MatrixXd part_weights(const std::vector<std::pair<BodyPart, std::vector<double>>>& given,
                             const std::vector<ComponentJoints>& components, const std::vector<double>& rest) {
  const Eigen::Index n = static_cast<Eigen::Index>(rest.size());
  std::vector<BodyPart> parts;
  for (const auto& [part, weights] : given) {
    if (static_cast<Eigen::Index>(weights.size()) != n)
      throw InputError("expected " + std::to_string(n) + " weights for " + body_part_name(part) + ", one per take, found " +
                       std::to_string(weights.size()));
    parts.push_back(part);
  }
  Eigen::MatrixXd out(static_cast<Eigen::Index>(components.size()), n);
  for (size_t c = 0; c < components.size(); ++c) {
    const int deciding = deciding_part(parts, components[c].region);
    const std::vector<double>& row = deciding >= 0 ? given[deciding].second : rest;
    for (Eigen::Index i = 0; i < n; ++i) out(static_cast<Eigen::Index>(c), i) = row[i];
  }
  return out;
}

Eigen::VectorXd source_frames_in_clip(const PreparedTakes& palette, const MixResult& mix) {
  // The reference's own frames (through its replays of cycles, when extended) in its file's rate.
  return frames_in_take(palette.takes.front(), mix.sources.col(0)) * (palette.takes.front().clip->fps() / palette.fps);
}

}  // namespace mostyle
