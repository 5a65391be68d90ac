#include "engine/run/pipeline.h"

#include <cmath>
#include <limits>
#include <string>

#include "engine/io/error.h"

namespace mostyle {

namespace {

// Into `mix` (its vectors reused, so a slider move allocates nothing once they are sized).
void set_blend_mix_params(const BlendParams& params, const Decomposed& d, MixParams& mix) {
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

}  // namespace

MixParams blend_mix_params(const BlendParams& params, const Decomposed& d) {
  if (!std::isfinite(params.alpha)) throw InputError("expected a finite alpha");
  MixParams mix;
  set_blend_mix_params(params, d, mix);
  return mix;
}

void blend_pair(const PreparedTakes& p, const Decomposed& d, const BlendParams& params, BlendScratch& s,
                BlendResult& out) {
  if (p.size() != 2)
    throw InputError("a blend of two takes was asked of " + std::to_string(p.size()) +
                     " takes; mix them with weights (mix)");
  if (!std::isfinite(params.alpha)) throw InputError("expected a finite alpha");
  MixParams& mix = s.mix_params;
  set_blend_mix_params(params, d, mix);
  mix_palette(p, d, mix, s.mix_scratch, s.mix);
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

Eigen::VectorXd source_frames_in_clip(const PreparedTakes& p, const BlendResult& blend) {
  return blend.source_a * (p.reference().clip->fps() / p.fps);
}

}  // namespace mostyle
