// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// How the engine's vectors grow: never at every new maximum (a trickle of
/// reallocations per cycle), but a few times in all.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace streamclust::detail {

/// Room for `n` elements, growing the capacity by at least half when it
/// falls short, for vectors sized to a count that rises slowly (components,
/// votes). O(1) when `n` fits, else O(size).
template <class T, class A>
void reserve_geometric(std::vector<T, A>& v, std::size_t n) {
  if (n > v.capacity()) v.reserve(std::max(n, v.capacity() + v.capacity() / 2));
}

/// Room for `n` elements in a per-window-point vector: when it cannot hold
/// them, `room` (>= n, the point rings' capacity), so such vectors allocate
/// only after the rings grew, never when a window merely reaches a new
/// maximum within them. O(1) when `n` fits, else O(size).
template <class T, class A>
void reserve_window(std::vector<T, A>& v, std::size_t n, std::size_t room) {
  if (n > v.capacity()) v.reserve(std::max(n, room));
}

}  // namespace streamclust::detail
