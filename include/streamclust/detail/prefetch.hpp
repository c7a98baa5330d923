// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A portable software-prefetch hint, shared by the engine and the indexes.

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
