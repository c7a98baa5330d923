// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Compiler and CPU hints for the hot paths: portable software prefetches and
/// inlining markers. None changes any result.

/// Forces inlining of a small hot function into its callers (GCC, clang);
/// plain `inline` elsewhere.
#if defined(__GNUC__) || defined(__clang__)
#define STREAMCLUST_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define STREAMCLUST_ALWAYS_INLINE inline
#endif

/// Keeps a rarely taken slow path (a growth) out of its hot caller.
#if defined(__GNUC__) || defined(__clang__)
#define STREAMCLUST_NOINLINE __attribute__((noinline))
#else
#define STREAMCLUST_NOINLINE
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

/// Hint that the cache line holding `p` will be written soon (no effect on
/// correctness). O(1), thread-safe.
inline void prefetch_for_write(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p, 1);
#else
  (void)p;
#endif
}

}  // namespace streamclust::detail
