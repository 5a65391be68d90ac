#pragma once
// A weighted sum of equal-length arrays of doubles, the mix's inner loop: out = sum_t w_t x_t,
// added term after term from zero, so that every element is rounded as
// `out.setZero(); for (t) out += w_t * x_t` rounds it (the same bits on every machine).
#include <cstddef>

namespace mostyle {

struct WeightedTerm {
  double weight = 0.0;
  const double* values = nullptr;
};

// out[0, length) = sum over terms[0, count) in order. Uses 256-bit vectors where the processor
// has them, in the same order of operations (no fused multiply-add), else plain loops.
void weighted_sum(const WeightedTerm* terms, int count, std::ptrdiff_t length, double* out);

}  // namespace mostyle
