#pragma once
// 256-bit vector code for the slider's hot loops, chosen when the program runs: the build keeps
// to the baseline instruction set so that one binary runs everywhere. A function marked
// MOSTYLE_TARGET_AVX may use <immintrin.h>'s AVX intrinsics; call it only where cpu_has_avx().
// AVX without FMA, so such a loop rounds as its plain version does.

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define MOSTYLE_HAS_AVX_PATH 1
#define MOSTYLE_TARGET_AVX __attribute__((target("avx")))
#include <immintrin.h>
#endif

namespace mostyle {

// Whether this processor runs AVX (false where the build has no AVX path).
bool cpu_has_avx();

}  // namespace mostyle
