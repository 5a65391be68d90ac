#include "engine/base/weighted_sum.h"

#include "engine/base/simd.h"

namespace mostyle {
namespace {

void weighted_sum_plain(const WeightedTerm* terms, int count, std::ptrdiff_t begin, std::ptrdiff_t length,
                        double* out) {
  for (std::ptrdiff_t c = begin; c < length; ++c) {
    double acc = 0.0;
    for (int t = 0; t < count; ++t) acc = acc + terms[t].weight * terms[t].values[c];
    out[c] = acc;
  }
}

#ifdef MOSTYLE_HAS_AVX_PATH
// Sixteen elements at a time in four accumulators, then four at a time; the last few plainly.
MOSTYLE_TARGET_AVX void weighted_sum_avx(const WeightedTerm* terms, int count, std::ptrdiff_t length,
                                                      double* out) {
  std::ptrdiff_t c = 0;
  for (; c + 16 <= length; c += 16) {
    __m256d a0 = _mm256_setzero_pd(), a1 = a0, a2 = a0, a3 = a0;
    for (int t = 0; t < count; ++t) {
      const __m256d w = _mm256_set1_pd(terms[t].weight);
      const double* x = terms[t].values + c;
      a0 = _mm256_add_pd(a0, _mm256_mul_pd(w, _mm256_loadu_pd(x)));
      a1 = _mm256_add_pd(a1, _mm256_mul_pd(w, _mm256_loadu_pd(x + 4)));
      a2 = _mm256_add_pd(a2, _mm256_mul_pd(w, _mm256_loadu_pd(x + 8)));
      a3 = _mm256_add_pd(a3, _mm256_mul_pd(w, _mm256_loadu_pd(x + 12)));
    }
    _mm256_storeu_pd(out + c, a0);
    _mm256_storeu_pd(out + c + 4, a1);
    _mm256_storeu_pd(out + c + 8, a2);
    _mm256_storeu_pd(out + c + 12, a3);
  }
  for (; c + 4 <= length; c += 4) {
    __m256d a = _mm256_setzero_pd();
    for (int t = 0; t < count; ++t)
      a = _mm256_add_pd(a, _mm256_mul_pd(_mm256_set1_pd(terms[t].weight), _mm256_loadu_pd(terms[t].values + c)));
    _mm256_storeu_pd(out + c, a);
  }
  weighted_sum_plain(terms, count, c, length, out);
}
#endif

}  // namespace

void weighted_sum(const WeightedTerm* terms, int count, std::ptrdiff_t length, double* out) {
#ifdef MOSTYLE_HAS_AVX_PATH
  if (cpu_has_avx()) {
    weighted_sum_avx(terms, count, length, out);
    return;
  }
#endif
  weighted_sum_plain(terms, count, 0, length, out);
}

}  // namespace mostyle
