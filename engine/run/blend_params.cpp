#include "engine/run/blend_params.h"

#include <cmath>
#include <limits>
#include <string>

#include "engine/base/error.h"

namespace mostyle {

void set_blend_mix_params(const BlendParams& params, const Decomposed& d, MixParams& mix) {
  if (!std::isfinite(params.alpha)) throw InputError("expected a finite alpha");
  const double alpha = params.alpha;
  mix.weights.assign({1.0 - alpha, alpha});
  if (d.shared() != nullptr && !params.component_alpha.empty()) {
    if (static_cast<int>(params.component_alpha.size()) != d.components())
      throw InputError("expected " + std::to_string(d.components()) + " component alphas, found " +
                       std::to_string(params.component_alpha.size()));
    mix.component_weights.resize(d.components(), 2);
    for (int c = 0; c < d.components(); ++c) {
      const double a = params.component_alpha[static_cast<size_t>(c)];
      if (!std::isfinite(a)) throw InputError("expected finite component alphas");
      mix.component_weights(c, 0) = 1.0 - a;
      mix.component_weights(c, 1) = a;
    }
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
