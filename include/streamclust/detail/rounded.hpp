// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `rounded(x)`: a float (or SSE vector of floats) the compiler must round
/// and keep as it is, so that the multiplication that produced it is never
/// fused with a following addition or subtraction into an FMA.
///
/// Why: with FMA instructions enabled (-mfma, -march=native, the aarch64
/// default) and GCC's default -ffp-contract=fast, `a * b + c` may be computed
/// with one rounding instead of two, and whether it is depends on the code
/// around it: a scalar and a vectorised evaluation of the same formula can then
/// differ in the last bit, and a linkage decision at its threshold with them.
/// Predicates whose evaluations must agree bit for bit (AngularLinkage's
/// pairwise operator and its `link_many`) pass every product that feeds a sum
/// through `rounded`. Without FMA contraction it changes nothing: IEEE
/// arithmetic already rounds every product. (-ffast-math, which reorders
/// sums, is outside what any of this can guarantee.)
///
/// Cost: an empty inline-assembly statement; no instruction, only a value the
/// optimiser cannot see through. O(1), thread-safe.

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace streamclust::detail {

/// `x`, rounded to float and opaque to the optimiser (see the file comment).
inline float rounded(float x) {
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__)) && defined(__SSE__)
  __asm__("" : "+x"(x));
#elif (defined(__GNUC__) || defined(__clang__)) && defined(__aarch64__)
  __asm__("" : "+w"(x));
#elif defined(__GNUC__) || defined(__clang__)
  __asm__("" : "+m"(x));
#endif
  return x;
}

#if defined(__SSE2__)
/// Four lanes of `rounded`.
inline __m128 rounded(__m128 x) {
#if defined(__GNUC__) || defined(__clang__)
  __asm__("" : "+x"(x));
#endif
  return x;
}
#endif

}  // namespace streamclust::detail
