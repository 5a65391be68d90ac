#include "engine/base/simd.h"

namespace mostyle {

bool cpu_has_avx() {
#ifdef MOSTYLE_HAS_AVX_PATH
  static const bool avx = __builtin_cpu_supports("avx");
  return avx;
#else
  return false;
#endif
}

}  // namespace mostyle
