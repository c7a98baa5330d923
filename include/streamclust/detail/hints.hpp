// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Compiler and CPU hints for the hot paths: a portable software prefetch and
/// a forced-inline marker. Neither changes any result.

/// Forces inlining of a small hot function into its callers (GCC, clang);
/// plain `inline` elsewhere.
#if defined(__GNUC__) || defined(__clang__)
#define STREAMCLUST_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define STREAMCLUST_ALWAYS_INLINE inline
#endif

namespace streamclust::detail {

/// Hint that the cache line holding `p` will be read soon (no effect on
/// correctness; a no-op on compilers without the builtin). O(1), thread-safe.
inline void prefetch(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

}  // namespace streamclust::detail
