#pragma once
// Four doubles, and four 64-bit integers, as GCC's and Clang's vector extensions hold them: one
// AVX register, or two SSE2 ones. Arithmetic on them is element by element, each element's the
// same operation in the same order as one double's (no fused multiply-add unless the function is
// compiled for it), so code written on four lanes gives the same values bit for bit as the same
// code on one.
namespace mostyle {

typedef double Doubles4 __attribute__((vector_size(32)));
typedef long long Integers4 __attribute__((vector_size(32)));

}  // namespace mostyle
