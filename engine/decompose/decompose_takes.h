#pragma once
// The second stage of the one chain (any number of takes, one code path): the takes prepared by prepare_takes
// (prepare_takes.h), decomposed into sparse components, X_i = W_i C. One value, in one of two
// forms:
//   shared (any number of takes; the editor's and the CLI's default): one set of components C
//     that every take shares, local (each a connected piece of the skeleton: a body part), and
//     each take's weights W_i; a mix blends the weights (mix_palette.h);
//   paper (two takes, the paper's own synthesis, 3.4 to 3.6): each take decomposed on its own,
//     or into its chain of basic motions (3.5) when DecomposeParams::basic_motions > 0.
// Both carry the same summary: each take's reconstruction error, the components' support and
// the joints each component moves.
#include <Eigen/Core>
#include <memory>
#include <variant>
#include <vector>

#include "engine/align/prepare_takes.h"
#include "engine/base/job_control.h"
#include "engine/base/stage_times.h"
#include "engine/decompose/basic_motions.h"
#include "engine/decompose/body_parts.h"
#include "engine/decompose/core_components.h"
#include "engine/decompose/decompose_params.h"
#include "engine/decompose/decomposition.h"

namespace mostyle {

// The stacked decomposition's components are fitted on at most this many frames (every take's
// samples at a stride): eight one-minute takes are 23 000 samples, and the components (body
// parts' shapes) need no more than a few per gait phase. The weights of every sample are then
// the least-squares fit to those components.
constexpr int kMaxDecompositionFrames = 6000;

// Shared mode: C shared by the takes, W_i per take.
struct SharedComponents {
  StackedDecomposition stacked;    // W_i (U x k) and C (k x 3M), normalized units
  // Per take, the reference's units, U x 3M: the components' reconstruction W_i C de-normalized,
  // and the residual (what the components do not hold). Their sum is the take's pose exactly.
  std::vector<Eigen::MatrixXd> reconstructed, residual;
  int stride = 1;                  // the components were fitted on every stride-th sample
};

// Paper mode: two takes, each decomposed on its own.
struct PaperComponents {
  Decomposition a, b;              // basic_motions == 0
  PaperSynthesis synthesis;        // A's weights, A's and B's cores (paper 3.6)
  BasicMotions basic_a, basic_b;   // basic_motions > 0
  BasicMotionSynthesis basic_synthesis;
};

struct Decomposed {
  DecomposeParams params;
  std::variant<SharedComponents, PaperComponents> form;
  // Summary, per take: reconstruction error (file units) and the fraction of non-zeros in its C.
  std::vector<double> rmse, nonzero;
  int iterations = 0;
  Eigen::MatrixXd support;         // k x 3M, 1 where a component is non-zero (A's in paper mode)
  std::vector<ComponentJoints> component_joints;  // per component: joints, centre, region, name
  int components() const { return params.components; }
  const SharedComponents* shared() const { return std::get_if<SharedComponents>(&form); }
  const PaperComponents* paper() const { return std::get_if<PaperComponents>(&form); }
};

// Throws InputError on bad parameters, or paper mode asked of more than two takes; Cancelled.
// Cost: shared mode, decompose() on N x U frames (at most kMaxDecompositionFrames of them) and
// N U x k by k x 3M products; paper mode, two decompositions of U frames (m each with basic
// motions). times: when given, its decompose_ms is set.
std::shared_ptr<const Decomposed> decompose_takes(const PreparedTakes& prepared, const DecomposeParams& params,
                                                  JobControl* control = nullptr, StageTimes* times = nullptr);

}  // namespace mostyle
