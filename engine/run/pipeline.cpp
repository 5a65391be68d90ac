#include "engine/run/pipeline.h"

#include <chrono>
#include <cmath>
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

const char* blend_mode_name(BlendMode mode) { return mode == BlendMode::kShared ? "shared" : "paper"; }

void DecomposeParams::Validate(int channels) const {
  if (components < 1 || components > channels)
    throw InputError("expected from 1 to " + std::to_string(channels) + " components, found " +
                     std::to_string(components));
  if (!(sparsity > 0 && sparsity <= 1))
    throw InputError("expected a sparsity in (0, 1], found " + std::to_string(sparsity));
  if (max_iterations < 0) throw InputError("expected 0 or more iterations, found " + std::to_string(max_iterations));
  if (!(tolerance >= 0) || !std::isfinite(tolerance))
    throw InputError("expected a tolerance of 0 or more, found " + std::to_string(tolerance));
  if (basic_motions < 0 || basic_motions > 16)
    throw InputError("expected from 0 to 16 basic motions, found " + std::to_string(basic_motions));
  if (basic_motions > 0 && mode != BlendMode::kPaper)
    throw InputError("basic motions are a paper-mode synthesis; use --mode paper with --basic");
  for (double f : basic_sparsities)
    if (!(f > 0 && f <= 1)) throw InputError("expected basic-motion sparsities in (0, 1], found " + std::to_string(f));
}

DecompositionOptions DecomposeParams::options(const std::vector<int>& parents) const {
  DecompositionOptions o;
  o.components = components;
  o.sparsity = sparsity;
  o.max_iterations = max_iterations;
  o.tolerance = tolerance;
  if (local) o.locality_parents = parents;
  return o;
}

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
    d->shared = decompose_shared(x_a, x_b, o, control);
    d->shared_synthesis = prepare_shared_synthesis(d->shared.weights_a, d->shared.weights_b, d->shared.components);
    const Eigen::MatrixXd reconstructed_a = synthesize_shared(d->shared_synthesis, 0.0);
    const Eigen::MatrixXd reconstructed_b = synthesize_shared(d->shared_synthesis, 1.0);
    d->residual_a = (x_a - reconstructed_a) * scale;
    d->residual_b = (x_b - reconstructed_b) * scale;
    d->local_a_components = reconstructed_a * scale;
    d->local_a_components.rowwise() += prepared.takes[0].mean;
    d->local_delta_components = reconstructed_b * scale;
    d->local_delta_components.rowwise() += prepared.takes[1].mean;
    d->local_delta_components -= d->local_a_components;
    d->local_a = d->local_a_components + d->residual_a;
    d->local_delta = d->local_delta_components + d->residual_b - d->residual_a;
    d->rmse_a = d->shared.rmse_a * scale;
    d->rmse_b = d->shared.rmse_b * scale;
    d->nonzero_a = d->nonzero_b = d->shared.nonzero_fraction;
    d->iterations = d->shared.iterations;
    support_source = &d->shared.components;
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
  const bool affine = d.params.mode == BlendMode::kShared && uniform;
  // The output timeline: output frame k sits at warp sample u[k] (align/timing.h).
  double timing = params.timing_a ? 0.0 : alpha;
  if (d.params.mode == BlendMode::kShared && !params.component_alpha.empty()) {
    if (static_cast<int>(params.component_alpha.size()) != d.components())
      throw InputError("expected " + std::to_string(d.components()) + " component alphas, found " +
                       std::to_string(params.component_alpha.size()));
    s.alphas = Eigen::Map<const Eigen::VectorXd>(params.component_alpha.data(), d.components());
    if (!params.timing_a) timing = s.alphas.mean();
  }
  blended_timeline(warp, timing, s.u);
  s.sampler.set(s.u, warp.samples());
  if (affine && params.residual) {
    // With the residuals, W_A C + residual_A is A's own pose: each take is read straight at the
    // (fractional) frame the output frame shows, (1 - alpha) A + alpha B, so alpha 0 is A's own
    // frames, not an interpolation of its warp samples.
    s.source_a.resize(s.u.size());
    s.source_b.resize(s.u.size());
    for (Eigen::Index k = 0; k < s.u.size(); ++k) {
      s.source_a[k] = value_at(warp.a, s.u[k]);
      s.source_b[k] = value_at(warp.b, s.u[k]);
    }
    s.sampler_a.set(s.source_a, a.canonical.local.rows());
    s.sampler_b.set(s.source_b, b.canonical.local.rows());
    s.sampler_a.apply(a.canonical.local, out.local);
    out.local *= 1.0 - alpha;
    s.sampler_b.accumulate(b.canonical.local, alpha, out.local);
  } else if (affine) {
    // local = (W_A + alpha (W_B - W_A)) C scale + mean_a + alpha (mean_b - mean_a), folded, at
    // the output frames only.
    s.sampler.apply_add(d.local_a_components, d.local_delta_components, alpha, out.local);
  } else if (d.params.mode == BlendMode::kShared) {  // one alpha per component
    synthesize_shared(d.shared_synthesis, s.alphas, s.x);
  } else if (d.params.basic_motions > 0) {
    synthesize_basic_motions(d.basic_synthesis, params.swap_level, alpha, s.x);
    s.x += d.basic_a.residual;  // the paper's chain sums back to X only with the residual
  } else {
    synthesize_paper(d.paper_synthesis, alpha, s.x);
  }
  out.synthesize_ms = ms_since(t0);

  const auto t1 = Clock::now();
  if (!affine) {
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
        s.samples.middleCols(3 * j, 3) += (1 - a) * d.residual_a.middleCols(3 * j, 3) + a * d.residual_b.middleCols(3 * j, 3);
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
