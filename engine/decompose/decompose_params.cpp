#include "engine/decompose/decompose_params.h"

#include <cmath>
#include <string>

#include "engine/base/error.h"

namespace mostyle {

const char* decomposition_mode_name(DecompositionMode mode) { return mode == DecompositionMode::kShared ? "shared" : "paper"; }

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
  if (basic_motions > 0 && mode != DecompositionMode::kPaper)
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

}  // namespace mostyle
