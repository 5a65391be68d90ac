#include "engine/run/pipeline.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "engine/io/error.h"
#include "engine/kinematics/limb_length.h"
#include "engine/prepare/major_take.h"
#include "engine/prepare/retarget.h"
#include "engine/align/timing.h"
#include "engine/post/finish.h"
#include <algorithm>

namespace mostyle {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// The blend's bones shorter than this fraction of their length lean on their previous direction
// (limb_length.h): two takes' hands pointing different ways average to a stub that would spin.
constexpr double kShortBoneFraction = 0.5;


}  // namespace

namespace {

void require_two(const PreparedTakes& prepared) {
  if (prepared.size() != 2)
    throw InputError("a blend of two takes was asked of " + std::to_string(prepared.size()) +
                     " takes; mix them with weights (mix)");
}

}  // namespace

std::shared_ptr<const DecomposedPair> decompose_pair(const PreparedTakes& prepared,
                                                     const DecomposeParams& params,
                                                     JobControl* control) {
  require_two(prepared);
  const Eigen::MatrixXd& x_a = prepared.takes[0].x;
  const Eigen::MatrixXd& x_b = prepared.takes[1].x;
  const int channels = static_cast<int>(x_a.cols());
  params.Validate(channels);
  const auto t0 = Clock::now();
  auto d = std::make_shared<DecomposedPair>();
  d->params = params;
  // Paper mode is never local (DecomposeParams::local).
  const DecompositionOptions o =
      params.options(params.mode == BlendMode::kShared ? prepared.parents : std::vector<int>());
  const double scale = prepared.scale;
  const Eigen::MatrixXd* support_source = nullptr;
  if (params.mode == BlendMode::kShared) {
    d->shared = decompose_palette(prepared, params, control);
    const StackedDecomposition& stacked = d->shared->stacked;
    d->shared_synthesis = prepare_shared_synthesis(stacked.weights[0], stacked.weights[1], stacked.components);
    d->rmse_a = d->shared->rmse[0];
    d->rmse_b = d->shared->rmse[1];
    d->nonzero_a = d->nonzero_b = stacked.nonzero_fraction;
    d->iterations = stacked.iterations;
    support_source = &stacked.components;
  } else if (params.basic_motions > 0) {
    BasicMotionOptions bo;
    bo.components = params.components;
    bo.max_iterations = params.max_iterations;
    bo.tolerance = params.tolerance;
    bo.sparsities.assign(params.basic_motions, params.sparsity);
    for (size_t i = 0; i < params.basic_sparsities.size() && i < bo.sparsities.size(); ++i)
      bo.sparsities[i] = params.basic_sparsities[i];
    d->basic_a = decompose_basic_motions(x_a, bo, control);
    d->basic_b = decompose_basic_motions(x_b, bo, control);
    d->basic_synthesis = prepare_basic_motion_synthesis(d->basic_a, d->basic_b);
    auto rmse = [&](const BasicMotions& m) {
      return std::sqrt(m.residual.squaredNorm() / std::max<double>(1, m.residual.size())) * scale;
    };
    d->rmse_a = rmse(d->basic_a);
    d->rmse_b = rmse(d->basic_b);
    d->nonzero_a = d->basic_a.levels.front().nonzero_fraction;
    d->nonzero_b = d->basic_b.levels.front().nonzero_fraction;
    for (const auto& level : d->basic_a.levels) d->iterations += level.iterations;
    support_source = &d->basic_a.levels.front().components;
  } else {
    d->paper_a = detail::decompose_part(x_a, o, control, 0.0f, 0.5f);
    d->paper_b = detail::decompose_part(x_b, o, control, 0.5f, 1.0f);
    d->paper_synthesis = prepare_paper_synthesis(d->paper_a.weights, core_components(d->paper_a.components),
                                                 core_components(d->paper_b.components));
    d->rmse_a = d->paper_a.rmse * scale;
    d->rmse_b = d->paper_b.rmse * scale;
    d->nonzero_a = d->paper_a.nonzero_fraction;
    d->nonzero_b = d->paper_b.nonzero_fraction;
    d->iterations = d->paper_a.iterations + d->paper_b.iterations;
    support_source = &d->paper_a.components;
  }
  d->support = (support_source->array() != 0.0).cast<double>();
  d->component_joints = describe_components(*support_source, prepared.majors);
  d->elapsed_ms = ms_since(t0);
  report_progress(control, 1.0f);
  return d;
}

namespace {

// v linearly interpolated at fractional index u (clamped).
double value_at(const Eigen::VectorXd& v, double u) {
  const Eigen::Index last = v.size() - 1;
  if (last <= 0) return v[0];
  const double at = std::clamp(u, 0.0, double(last));
  const Eigen::Index i = std::min<Eigen::Index>(static_cast<Eigen::Index>(at), last - 1);
  const double f = at - double(i);
  return (1 - f) * v[i] + f * v[i + 1];
}

// One alpha in shared mode: the mix of the two takes with weights (1 - alpha, alpha) (palette.h).
void blend_as_mix(const PreparedTakes& p, const DecomposedPair& d, const BlendParams& params, BlendScratch& s,
                  BlendResult& out) {
  MixParams& mix = s.mix_params;
  mix.weights.assign({1.0 - params.alpha, params.alpha});
  mix.min_weight = -std::numeric_limits<double>::infinity();  // any alpha: how far to exaggerate is the person's call
  mix.max_weight = std::numeric_limits<double>::infinity();
  mix.reference_timing = params.timing_a;
  mix.residual = params.residual;
  mix.root_pull_seconds = params.root_pull_seconds;
  mix.finish.limb_lengths = params.limb_lengths;
  mix.finish.foot_lock = params.foot_lock;
  mix.finish.loop = params.loop;
  mix_palette(p, *d.shared, mix, s.mix_scratch, s.mix);
  FinishedMotion& m = s.mix.motion;
  out.world.swap(m.world);
  out.contacts.swap(m.contacts);
  out.loop = m.loop;
  out.limb_length_max_error = m.limb_length_max_error;
  out.foot_sliding_raw = m.foot_sliding_raw;
  out.foot_sliding_cleaned = m.foot_sliding_cleaned;
  out.local.swap(s.mix.local);
  out.sample.swap(s.mix.sample);
  out.source_a = s.mix.sources.col(0);
  out.source_b = s.mix.sources.col(1);
  out.synthesize_ms = s.mix.synthesize_ms;
  out.postprocess_ms = s.mix.postprocess_ms;
}

}  // namespace

void blend_pair(const PreparedTakes& p, const DecomposedPair& d, const BlendParams& params,
                BlendScratch& s, BlendResult& out) {
  require_two(p);
  if (!std::isfinite(params.alpha)) throw InputError("expected a finite alpha");
  const auto t0 = Clock::now();
  const double alpha = params.alpha;
  const PreparedTake& a = p.takes[0];
  const PreparedTake& b = p.takes[1];
  const TimeWarp& warp = b.alignment.warp;
  // Per-component alphas all equal to alpha are the plain blend.
  const bool uniform = std::all_of(params.component_alpha.begin(), params.component_alpha.end(),
                                   [&](double a) { return a == alpha; });
  if (d.params.mode == BlendMode::kShared && !params.component_alpha.empty() &&
      static_cast<int>(params.component_alpha.size()) != d.components())
    throw InputError("expected " + std::to_string(d.components()) + " component alphas, found " +
                     std::to_string(params.component_alpha.size()));
  if (d.params.mode == BlendMode::kShared && uniform) {
    blend_as_mix(p, d, params, s, out);
    return;
  }
  // The output timeline: output frame k sits at warp sample u[k] (align/timing.h).
  double timing = params.timing_a ? 0.0 : alpha;
  if (d.params.mode == BlendMode::kShared && !params.component_alpha.empty()) {
    s.alphas = Eigen::Map<const Eigen::VectorXd>(params.component_alpha.data(), d.components());
    if (!params.timing_a) timing = s.alphas.mean();
  }
  blended_timeline(warp, timing, s.u);
  s.sampler.set(s.u, warp.samples());
  if (d.params.mode == BlendMode::kShared) {  // one alpha per component
    synthesize_shared(d.shared_synthesis, s.alphas, s.x);
  } else if (d.params.basic_motions > 0) {
    synthesize_basic_motions(d.basic_synthesis, params.swap_level, alpha, s.x);
    s.x += d.basic_a.residual;  // the paper's chain sums back to X only with the residual
  } else {
    synthesize_paper(d.paper_synthesis, alpha, s.x);
  }
  out.synthesize_ms = ms_since(t0);

  const auto t1 = Clock::now();
  {
    s.mean.noalias() = (1 - alpha) * a.mean + alpha * b.mean;
    s.samples.resize(s.x.rows(), s.x.cols());
    s.samples.noalias() = s.x * p.scale;
    s.samples.rowwise() += s.mean;
    if (params.residual && d.params.mode == BlendMode::kShared) {
      // Per-component alphas: each joint's residual takes the mean alpha of the components
      // that move it (a body part's detail follows that part), the overall mean elsewhere.
      s.joint_alpha = joint_values(d.support, s.alphas);
      for (Eigen::Index j = 0; j < s.joint_alpha.rows(); ++j) {
        const double a = s.joint_alpha(j, 0);
        s.samples.middleCols(3 * j, 3) +=
            (1 - a) * d.shared->residual[0].middleCols(3 * j, 3) + a * d.shared->residual[1].middleCols(3 * j, 3);
      }
    }
    s.sampler.apply(s.samples, out.local);
  }
  // The root on the warp's samples, then at the output frames.
  s.steps.resize(a.steps.rows(), 3);
  s.steps.noalias() = (1 - alpha) * a.steps + alpha * b.steps;
  // B's whole-turn flips (prepare_takes), spread over a moment (canonical_frame.h).
  add_spread_turns(b.turn_flips, alpha, p.fps, s.steps);
  integrate_blended_root(s.steps, a.ground, b.ground, alpha, p.reference_heading[0], p.fps,
                         params.root_pull_seconds, &s.ground_u, &s.heading_u);
  // Foot contacts mixed with the same alpha (the mean one when each component has its own).
  const double contact_alpha = d.params.mode == BlendMode::kShared && !params.component_alpha.empty() ? s.alphas.mean() : alpha;
  blend_contacts(a.contacts, b.contacts, contact_alpha, s.contacts_u);
  FinishRig rig;
  rig.parents = &p.parents;
  rig.lengths = &p.lengths;
  rig.feet = &p.feet;
  rig.short_bone_fraction = kShortBoneFraction;
  FinishOptions finish;
  finish.limb_lengths = params.limb_lengths;
  finish.foot_lock = params.foot_lock;
  finish.loop = params.loop;
  finish_motion(s.sampler, s.ground_u, s.heading_u, s.contacts_u, rig, finish, out.local, s.u, s.finish, s.finished);
  out.world.swap(s.finished.world);
  out.contacts.swap(s.finished.contacts);
  out.loop = s.finished.loop;
  out.limb_length_max_error = s.finished.limb_length_max_error;
  out.foot_sliding_raw = s.finished.foot_sliding_raw;
  out.foot_sliding_cleaned = s.finished.foot_sliding_cleaned;
  out.sample = s.u;
  out.source_a.resize(s.u.size());
  out.source_b.resize(s.u.size());
  for (Eigen::Index k = 0; k < s.u.size(); ++k) {
    out.source_a[k] = value_at(warp.a, s.u[k]);
    out.source_b[k] = value_at(warp.b, s.u[k]);
  }
  out.postprocess_ms = ms_since(t1);
}

Eigen::VectorXd source_frames_in_clip(const PreparedTakes& p, const BlendResult& blend) {
  return blend.source_a * (p.reference().clip->fps() / p.fps);
}

}  // namespace mostyle
