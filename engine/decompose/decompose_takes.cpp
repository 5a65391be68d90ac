#include "engine/decompose/decompose_takes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include <Eigen/QR>

#include "engine/base/clock.h"
#include "engine/base/error.h"

namespace mostyle {
namespace {

using Clock = std::chrono::steady_clock;
// Shared mode: the takes stacked, one C, each take's W_i; returns C.
const Eigen::MatrixXd& decompose_shared_mode(const PreparedTakes& p, const DecomposeParams& params, JobControl* control,
                                             Decomposed& d) {
  SharedComponents& s = d.form.emplace<SharedComponents>();
  const DecompositionOptions o = params.options(p.parents);
  // Fitted on every stride-th sample when the takes are long (kMaxDecompositionFrames).
  const Eigen::Index total = static_cast<Eigen::Index>(p.samples()) * p.size();
  s.stride = static_cast<int>(std::max<Eigen::Index>(1, (total + kMaxDecompositionFrames - 1) / kMaxDecompositionFrames));
  std::vector<Eigen::MatrixXd> strided;
  std::vector<const Eigen::MatrixXd*> xs;
  for (const PreparedTake& t : p.takes) {
    if (s.stride == 1) {
      xs.push_back(&t.x);
      continue;
    }
    const Eigen::Index rows = (t.x.rows() + s.stride - 1) / s.stride;
    strided.emplace_back(rows, t.x.cols());
    for (Eigen::Index r = 0; r < rows; ++r) strided.back().row(r) = t.x.row(r * s.stride);
  }
  for (const Eigen::MatrixXd& x : strided) xs.push_back(&x);
  s.stacked = decompose_stacked(xs, o, control);
  if (s.stride > 1) {
    // Every sample's weights: the least-squares fit to the components, W = X C^T (C C^T)^+.
    const Eigen::MatrixXd& c = s.stacked.components;
    const Eigen::MatrixXd gram = c * c.transpose();
    const auto solver = gram.completeOrthogonalDecomposition();
    for (size_t i = 0; i < p.takes.size(); ++i) {
      const Eigen::MatrixXd& x = p.takes[i].x;
      s.stacked.weights[i] = solver.solve(c * x.transpose()).transpose();
      s.stacked.rmse[i] = std::sqrt((x - s.stacked.weights[i] * c).squaredNorm() / double(x.size()));
    }
  }
  for (size_t i = 0; i < p.takes.size(); ++i) {
    const PreparedTake& t = p.takes[i];
    const Eigen::MatrixXd wc = s.stacked.weights[i] * s.stacked.components;
    s.residual.push_back((t.x - wc) * p.scale);
    Eigen::MatrixXd r = wc * p.scale;
    r.rowwise() += t.mean;
    s.reconstructed.push_back(std::move(r));
    d.rmse.push_back(s.stacked.rmse[i] * p.scale);
    d.nonzero.push_back(s.stacked.nonzero_fraction);
  }
  d.iterations = s.stacked.iterations;
  return s.stacked.components;
}

// Paper mode: each of the two takes on its own (paper 3.4), or its chain of basic motions (3.5);
// returns A's components. Never local (DecomposeParams::local).
const Eigen::MatrixXd& decompose_paper_mode(const PreparedTakes& p, const DecomposeParams& params, JobControl* control,
                                            Decomposed& d) {
  PaperComponents& c = d.form.emplace<PaperComponents>();
  const Eigen::MatrixXd& x_a = p.takes[0].x;
  const Eigen::MatrixXd& x_b = p.takes[1].x;
  if (params.basic_motions > 0) {
    BasicMotionOptions bo;
    bo.components = params.components;
    bo.max_iterations = params.max_iterations;
    bo.tolerance = params.tolerance;
    bo.sparsities.assign(params.basic_motions, params.sparsity);
    for (size_t i = 0; i < params.basic_sparsities.size() && i < bo.sparsities.size(); ++i)
      bo.sparsities[i] = params.basic_sparsities[i];
    c.basic_a = decompose_basic_motions(x_a, bo, control);
    c.basic_b = decompose_basic_motions(x_b, bo, control);
    c.basic_synthesis = prepare_basic_motion_synthesis(c.basic_a, c.basic_b);
    for (const BasicMotions* m : {&c.basic_a, &c.basic_b}) {
      d.rmse.push_back(std::sqrt(m->residual.squaredNorm() / std::max<double>(1, m->residual.size())) * p.scale);
      d.nonzero.push_back(m->levels.front().nonzero_fraction);
    }
    for (const auto& level : c.basic_a.levels) d.iterations += level.iterations;
    return c.basic_a.levels.front().components;
  }
  const DecompositionOptions o = params.options({});
  c.a = detail::decompose_part(x_a, o, control, 0.0f, 0.5f);
  c.b = detail::decompose_part(x_b, o, control, 0.5f, 1.0f);
  c.synthesis = prepare_paper_synthesis(c.a.weights, core_components(c.a.components), core_components(c.b.components));
  for (const Decomposition* one : {&c.a, &c.b}) {
    d.rmse.push_back(one->rmse * p.scale);
    d.nonzero.push_back(one->nonzero_fraction);
  }
  d.iterations = c.a.iterations + c.b.iterations;
  return c.a.components;
}

}  // namespace

std::shared_ptr<const Decomposed> decompose_takes(const PreparedTakes& prepared, const DecomposeParams& params,
                                                  JobControl* control, StageTimes* times) {
  params.Validate(static_cast<int>(prepared.reference().x.cols()));
  if (params.mode != DecompositionMode::kShared && prepared.size() != 2)
    throw InputError("several takes mix shared components; paper mode and basic motions blend two takes (use blend)");
  const auto t0 = Clock::now();
  auto d = std::make_shared<Decomposed>();
  d->params = params;
  const Eigen::MatrixXd& components = params.mode == DecompositionMode::kShared
                                          ? decompose_shared_mode(prepared, params, control, *d)
                                          : decompose_paper_mode(prepared, params, control, *d);
  d->support = (components.array() != 0.0).cast<double>();
  d->component_joints = describe_components(components, prepared.majors);
  if (times != nullptr) times->decompose_ms = ms_since(t0);
  report_progress(control, 1.0f);
  return d;
}

}  // namespace mostyle
