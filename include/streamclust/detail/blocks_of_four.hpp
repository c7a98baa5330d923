// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The block walk of the SIMD `link_many` paths: slots four at a time, the
/// last one to three in one more block padded with repeats.

#include <streamclust/detail/hints.hpp>

#include <cstddef>
#include <cstdint>

namespace streamclust::detail {

/// Calls `decide_four(const std::uint32_t* four_slots, std::uint8_t* four_out)`
/// on slots[0, count) four at a time; the last count % 4 go in one more
/// block padded with repeats of their first slot, whose extra decisions are
/// dropped. Writes linked[0, count). O(count).
template <class DecideFour>
STREAMCLUST_ALWAYS_INLINE void in_blocks_of_four(const std::uint32_t* slots, std::size_t count, std::uint8_t* linked,
                                                 DecideFour&& decide_four) {
  std::size_t k = 0;
  for (; k + 4 <= count; k += 4) decide_four(slots + k, linked + k);
  if (k < count) {
    const std::size_t rest = count - k;  // 1 to 3
    const std::uint32_t padded[4] = {slots[k], slots[k + (rest > 1 ? 1 : 0)], slots[k + (rest > 2 ? 2 : 0)], slots[k]};
    std::uint8_t decided[4];
    decide_four(padded, decided);
    for (std::size_t i = 0; i < rest; ++i) linked[k + i] = decided[i];
  }
}

}  // namespace streamclust::detail
