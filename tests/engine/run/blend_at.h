#pragma once
// One blend with fresh scratch, for tests of the pipeline.
#include "engine/run/pipeline.h"

namespace mostyle::test {

inline BlendResult blend_at(const PreparedTakes& p, const Decomposed& d, double alpha, BlendParams params = {}) {
  params.alpha = alpha;
  BlendScratch scratch;
  BlendResult out;
  blend_pair(p, d, params, scratch, out);
  return out;
}

}  // namespace mostyle::test
