#include "engine/run/blend_params.h"

#include <cmath>
#include <limits>
#include <string>

#include "engine/base/error.h"

namespace mostyle {

void set_component_alpha_weights(const std::vector<double>& alphas, Eigen::MatrixXd& out) {
  out.resize(static_cast<Eigen::Index>(alphas.size()), 2);
  for (size_t c = 0; c < alphas.size(); ++c) {
    const double a = alphas[c];
    if (!std::isfinite(a)) throw InputError("expected finite component alphas");
    out(static_cast<Eigen::Index>(c), 0) = 1.0 - a;
    out(static_cast<Eigen::Index>(c), 1) = a;
  }
}

void set_blend_mix_params(const BlendParams& params, const Decomposed& d, MixParams& mix) {
  if (!std::isfinite(params.alpha)) throw InputError("expected a finite alpha");
  const double alpha = params.alpha;
  mix.weights.assign({1.0 - alpha, alpha});
  if (d.shared() != nullptr && !params.component_alpha.empty()) {
    if (static_cast<int>(params.component_alpha.size()) != d.components())
      throw InputError("expected " + std::to_string(d.components()) + " component alphas, found " +
                       std::to_string(params.component_alpha.size()));
    set_component_alpha_weights(params.component_alpha, mix.component_weights);
  } else {
    mix.component_weights.resize(0, 0);
  }
  // Any alpha: how far to exaggerate is the person's call.
  mix.min_weight = -std::numeric_limits<double>::infinity();
  mix.max_weight = std::numeric_limits<double>::infinity();
  mix.swap_level = params.swap_level;
  mix.reference_timing = params.timing_a;
  mix.residual = params.residual;
  mix.root_pull_seconds = params.root_pull_seconds;
  mix.finish.limb_lengths = params.limb_lengths;
  mix.finish.foot_lock = params.foot_lock;
  mix.finish.loop = params.loop;
}

MixParams blend_mix_params(const BlendParams& params, const Decomposed& d) {
  MixParams mix;
  set_blend_mix_params(params, d, mix);
  return mix;
}

}  // namespace mostyle
