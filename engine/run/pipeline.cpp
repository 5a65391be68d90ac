#include "engine/run/pipeline.h"

#include <chrono>
#include <cmath>
#include <string>

#include "engine/io/error.h"
#include "engine/kinematics/limb_length.h"
#include "engine/prepare/major_take.h"
#include "engine/prepare/retarget.h"

namespace mostyle {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

constexpr double kMaxFps = 1000.0;

Eigen::MatrixXd column_block(const Eigen::MatrixXd& m, int joint) { return m.middleCols(3 * joint, 3); }

}  // namespace

void PrepareOptions::Validate() const {
  if (!(fps >= 0) || fps > kMaxFps || !std::isfinite(fps))
    throw InputError("expected a frame rate from 1 to 1000 (or 0 to keep A's), found " + std::to_string(fps));
  if (dtw_band < -1) throw InputError("expected a DTW band of 0 or more frames, found " + std::to_string(dtw_band));
  foot_contacts.Validate();
}

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

std::shared_ptr<const PreparedPair> prepare_pair(std::shared_ptr<const Clip> a,
                                                 std::shared_ptr<const Clip> b,
                                                 const PrepareOptions& options,
                                                 JobControl* control) {
  options.Validate();
  const auto t0 = Clock::now();
  auto p = std::make_shared<PreparedPair>();
  p->clip_a = a;
  p->clip_b = b;
  p->mapping_a = map_major_joints(a->skeleton, options.mapping_a.entries.empty() ? nullptr : &options.mapping_a);
  p->mapping_b = map_major_joints(b->skeleton, options.mapping_b.entries.empty() ? nullptr : &options.mapping_b);
  p->majors = shared_major_joints(p->mapping_a, a->source, p->mapping_b, b->source);
  p->parents = subset_parents(p->majors);
  const double fps = options.fps > 0 ? options.fps : a->fps();
  p->fps = fps;
  report_progress(control, 0.1f);
  const MajorTake take_a = extract_major_take(*a, p->mapping_a, p->majors, fps);
  check_cancel(control);
  const MajorTake take_b = extract_major_take(*b, p->mapping_b, p->majors, fps);
  check_cancel(control);
  p->names_a = take_a.names;
  p->names_b = take_b.names;
  p->world_a = take_a.world;

  auto column = [&](MajorJoint j) { return major_column(p->majors, static_cast<int>(j)); };
  const int leg[6] = {column(MajorJoint::kLeftHip), column(MajorJoint::kLeftKnee),
                      column(MajorJoint::kLeftAnkle), column(MajorJoint::kRightHip),
                      column(MajorJoint::kRightKnee), column(MajorJoint::kRightAnkle)};
  p->left_ankle = leg[2];
  p->right_ankle = leg[5];
  p->left_toe = column(MajorJoint::kLeftToe);
  p->right_toe = column(MajorJoint::kRightToe);
  p->lengths_a = bone_lengths(take_a.world, p->parents);
  const std::vector<double> lengths_b = bone_lengths(take_b.world, p->parents);
  p->world_b = retarget_positions(take_b.world, p->parents, p->lengths_a, leg_length(p->lengths_a, leg),
                                  leg_length(lengths_b, leg));
  adopt_group_shapes(p->world_b, p->world_a, p->parents);
  apply_limb_lengths(p->world_b, p->parents, p->lengths_a);
  p->canonical_a = to_canonical(p->world_a, 0, leg[0], leg[3]);
  p->canonical_b = to_canonical(p->world_b, 0, leg[0], leg[3]);
  p->signal_a = column_block(p->canonical_a.local, p->left_ankle);
  p->signal_b = column_block(p->canonical_b.local, p->left_ankle);
  p->times.preprocess_ms = ms_since(t0);
  report_progress(control, 0.3f);

  const auto t1 = Clock::now();
  DtwOptions dtw;
  dtw.band = options.dtw_band;
  p->path = align_dtw(p->signal_a, p->signal_b, dtw, control);
  p->times.dtw_ms = ms_since(t1);
  report_progress(control, 0.8f);

  const auto t2 = Clock::now();
  const int frames = static_cast<int>(p->world_a.rows());
  p->warp = warp_map(p->path, frames);
  p->local_b = warp_onto(p->canonical_b.local, p->path, frames);
  const Eigen::MatrixXd ground_b = warp_onto(p->canonical_b.ground, p->path, frames);
  const Eigen::VectorXd heading_b = warp_onto(Eigen::MatrixXd(p->canonical_b.heading), p->path, frames);
  p->steps_a = root_steps(p->canonical_a);
  // B's root on A's timeline: no teleport where the warp skips B frames, and facings that blend
  // along the short arc (canonical_frame.h).
  p->steps_b = match_turns(limit_warped_steps(root_steps(ground_b, heading_b), p->warp, kMaxWarpSpeedup), p->steps_a);
  p->normalization = fit_normalization(p->canonical_a.local, p->local_b);
  p->x_a = normalize(p->canonical_a.local, p->normalization.mean_a, p->normalization.scale);
  p->x_b = normalize(p->local_b, p->normalization.mean_b, p->normalization.scale);
  Eigen::MatrixXd ground;
  Eigen::VectorXd heading;
  integrate_root(p->steps_b, p->canonical_a.ground.row(0).transpose(), p->canonical_a.heading[0], &ground,
                 &heading);
  to_world(p->local_b, ground, heading, &p->world_b_on_a);
  apply_limb_lengths(p->world_b_on_a, p->parents, p->lengths_a);  // the warp interpolates positions
  p->ground_b_on_a = ground;
  // Foot contacts of each take on its own motion, B's carried onto A's timeline by the warp, so
  // blend_pair only mixes them (foot_contact.h).
  p->feet = make_foot_rig(p->majors, p->lengths_a, fps, options.foot_contacts);
  p->contacts_a = detect_foot_contacts(p->world_a, p->feet);
  p->contacts_b = detect_foot_contacts(p->world_b, p->feet);
  p->contacts_b_on_a = carry_contacts(p->contacts_b, p->warp);
  p->foot_sliding_a = foot_sliding(p->world_a, p->contacts_a, p->feet);
  p->foot_sliding_b = foot_sliding(p->world_b, p->contacts_b, p->feet);
  p->times.preprocess_ms += ms_since(t2);
  report_progress(control, 1.0f);
  return p;
}

std::shared_ptr<const DecomposedPair> decompose_pair(const PreparedPair& prepared,
                                                     const DecomposeParams& params,
                                                     JobControl* control) {
  const int channels = static_cast<int>(prepared.x_a.cols());
  params.Validate(channels);
  const auto t0 = Clock::now();
  auto d = std::make_shared<DecomposedPair>();
  d->params = params;
  DecompositionOptions o;
  o.components = params.components;
  o.sparsity = params.sparsity;
  o.max_iterations = params.max_iterations;
  o.tolerance = params.tolerance;
  const double scale = prepared.normalization.scale;
  const Eigen::MatrixXd* support_source = nullptr;
  if (params.mode == BlendMode::kShared) {
    d->shared = decompose_shared(prepared.x_a, prepared.x_b, o, control);
    d->shared_synthesis = prepare_shared_synthesis(d->shared.weights_a, d->shared.weights_b, d->shared.components);
    const Normalization& n = prepared.normalization;
    d->local_a = synthesize_shared(d->shared_synthesis, 0.0) * scale;
    d->local_a.rowwise() += n.mean_a;
    d->local_delta = synthesize_shared(d->shared_synthesis, 1.0) * scale;
    d->local_delta.rowwise() += n.mean_b;
    d->local_delta -= d->local_a;
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
    d->basic_a = decompose_basic_motions(prepared.x_a, bo, control);
    d->basic_b = decompose_basic_motions(prepared.x_b, bo, control);
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
    d->paper_a = detail::decompose_part(prepared.x_a, o, control, 0.0f, 0.5f);
    d->paper_b = detail::decompose_part(prepared.x_b, o, control, 0.5f, 1.0f);
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
  d->elapsed_ms = ms_since(t0);
  report_progress(control, 1.0f);
  return d;
}

void blend_pair(const PreparedPair& p, const DecomposedPair& d, const BlendParams& params,
                BlendScratch& s, BlendResult& out) {
  if (!std::isfinite(params.alpha)) throw InputError("expected a finite alpha");
  const auto t0 = Clock::now();
  const double alpha = params.alpha;
  const Normalization& n = p.normalization;
  const bool affine = d.params.mode == BlendMode::kShared && params.component_alpha.empty();
  if (affine) {
    // local = (W_A + alpha (W_B - W_A)) C scale + mean_a + alpha (mean_b - mean_a), folded.
    s.local.resize(d.local_a.rows(), d.local_a.cols());
    s.local.noalias() = d.local_a + alpha * d.local_delta;
  } else if (d.params.mode == BlendMode::kShared) {  // one alpha per component
    if (static_cast<int>(params.component_alpha.size()) != d.components())
      throw InputError("expected " + std::to_string(d.components()) + " component alphas, found " +
                       std::to_string(params.component_alpha.size()));
    s.alphas = Eigen::Map<const Eigen::VectorXd>(params.component_alpha.data(), d.components());
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
    s.mean.noalias() = (1 - alpha) * n.mean_a + alpha * n.mean_b;
    s.local.resize(s.x.rows(), s.x.cols());
    s.local.noalias() = s.x * n.scale;
    s.local.rowwise() += s.mean;
  }
  s.steps.resize(p.steps_a.rows(), 3);
  s.steps.noalias() = (1 - alpha) * p.steps_a + alpha * p.steps_b;
  integrate_blended_root(s.steps, p.canonical_a.ground, p.ground_b_on_a, alpha, p.canonical_a.heading[0], p.fps,
                         params.root_pull_seconds, &s.ground, &s.heading);
  to_world(s.local, s.ground, s.heading, &out.world);
  if (params.limb_lengths) apply_limb_lengths(out.world, p.parents, p.lengths_a);
  // Foot lock (beyond the paper): contacts mixed with the same alpha (the mean one when each
  // component has its own), planted ankles pinned by two-bone IK, which keeps bone lengths.
  double contact_alpha = alpha;
  if (d.params.mode == BlendMode::kShared && !params.component_alpha.empty()) contact_alpha = s.alphas.mean();
  blend_contacts(p.contacts_a, p.contacts_b_on_a, contact_alpha, out.contacts);
  out.foot_sliding_raw = foot_sliding(out.world, out.contacts, p.feet);
  if (params.foot_lock) apply_foot_lock(out.world, out.contacts, p.feet, s.foot);
  out.foot_sliding_cleaned = params.foot_lock ? foot_sliding(out.world, out.contacts, p.feet) : out.foot_sliding_raw;
  out.limb_length_max_error = max_bone_length_error(out.world, p.parents, p.lengths_a);
  out.postprocess_ms = ms_since(t1);
}

}  // namespace mostyle
