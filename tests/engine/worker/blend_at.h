#pragma once
// One blend (the mix of two takes as two layers, 1 - alpha and alpha: mix_layers.h) with fresh
// scratch, for tests of the pipeline.
#include <utility>
#include <vector>

#include "engine/synthesize/mix_palette.h"

namespace mostyle::test {

// `params` blending at alpha: A's layer at 1 - alpha, B's at alpha, with `component_alphas` (one
// per component; empty: none) per component (1 - alpha_c, alpha_c). The layers are rewritten in
// place: once they are sized, another alpha allocates nothing.
inline void set_blend(double alpha, MixParams& params, const std::vector<double>& component_alphas = {}) {
  params.layers.additive.clear();
  params.layers.layers.resize(2);
  for (int i = 0; i < 2; ++i) {
    MixLayer& layer = params.layers.layers[static_cast<size_t>(i)];
    layer.take = i;
    layer.weight = i == 0 ? 1.0 - alpha : alpha;
    layer.component_weights.resize(component_alphas.size());
    for (size_t c = 0; c < component_alphas.size(); ++c)
      layer.component_weights[c] = i == 0 ? 1.0 - component_alphas[c] : component_alphas[c];
  }
}

inline MixResult blend_at(const PreparedTakes& p, const Decomposed& d, double alpha, MixParams params = {},
                          const std::vector<double>& component_alphas = {}) {
  set_blend(alpha, params, component_alphas);
  MixScratch scratch;
  MixResult out;
  mix_palette(p, d, params, scratch, out);
  return out;
}

// A blend into `out` reusing `run` (what the editor does on each slider move): `options` at alpha
// (set_blend), then mix_palette.
struct BlendRun {
  MixParams params;
  MixScratch scratch;
};
inline void blend_into(const PreparedTakes& p, const Decomposed& d, double alpha, const MixParams& options,
                       BlendRun& run, MixResult& out, StageTimes* times = nullptr,
                       const std::vector<double>& component_alphas = {}) {
  MixLayers layers;  // the layers kept across the copy of the options: resized, not made again
  std::swap(layers, run.params.layers);
  run.params = options;
  std::swap(layers, run.params.layers);
  set_blend(alpha, run.params, component_alphas);
  mix_palette(p, d, run.params, run.scratch, out, times);
}

}  // namespace mostyle::test
