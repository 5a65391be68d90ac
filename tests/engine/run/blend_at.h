#pragma once
// One blend (the mix of two takes with weights (1 - alpha, alpha), blend_params.h) with fresh
// scratch, for tests of the pipeline.
#include "engine/run/blend_params.h"
#include "engine/synthesize/mix_palette.h"

namespace mostyle::test {

inline MixResult blend_at(const PreparedTakes& p, const Decomposed& d, double alpha, BlendParams params = {}) {
  params.alpha = alpha;
  MixScratch scratch;
  MixResult out;
  mix_palette(p, d, blend_mix_params(params, d), scratch, out);
  return out;
}

// A blend into `out` reusing `run` (what the editor does on each slider move): the blend's mix
// parameters (set_blend_mix_params), then mix_palette.
struct BlendRun {
  MixParams params;
  MixScratch scratch;
};
inline void blend_into(const PreparedTakes& p, const Decomposed& d, const BlendParams& blend, BlendRun& run,
                       MixResult& out, StageTimes* times = nullptr) {
  set_blend_mix_params(blend, d, run.params);
  mix_palette(p, d, run.params, run.scratch, out, times);
}

}  // namespace mostyle::test
