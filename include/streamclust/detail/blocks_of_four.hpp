// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The block walk of the SIMD `link_many` paths (slots four at a time, the
/// last one to three in one more block padded with repeats) and, with SSE2,
/// the load and store every four-lane decision shares.

#include <streamclust/detail/hints.hpp>
#include <streamclust/detail/rounded.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <cstddef>
#include <cstdint>
#include <type_traits>

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

#if defined(__SSE2__)
/// Four payloads of four floats each, one component per register: x[i] is
/// payload i's first float, w[i] its fourth.
struct FourColumns {
  __m128 x, y, z, w;
};

/// The payloads ring[slots[i]] for i < 4 (each four floats, 16 bytes,
/// 16-aligned, standard layout), transposed. O(1).
template <class Payload>
STREAMCLUST_ALWAYS_INLINE FourColumns load_four_columns(const Payload* ring, const std::uint32_t* slots) {
  static_assert(sizeof(Payload) == 4 * sizeof(float) && alignof(Payload) == 16 &&
                    std::is_standard_layout_v<Payload>,
                "load_four_columns: a payload is four floats, 16-aligned");
  const auto row = [&](std::size_t i) { return _mm_load_ps(reinterpret_cast<const float*>(ring + slots[i])); };
  FourColumns c{row(0), row(1), row(2), row(3)};
  _MM_TRANSPOSE4_PS(c.x, c.y, c.z, c.w);
  return c;
}

/// The squared distances from (ax, ay, az) to the four points (b.x, b.y,
/// b.z), operation by operation as the scalar dx*dx + dy*dy + dz*dz (each
/// product rounded: never fused with the sum). O(1).
STREAMCLUST_ALWAYS_INLINE __m128 squared_distances_four(__m128 ax, __m128 ay, __m128 az, const FourColumns& b) {
  const auto mul = [](__m128 x, __m128 y) { return rounded(_mm_mul_ps(x, y)); };
  const __m128 dx = _mm_sub_ps(ax, b.x);
  const __m128 dy = _mm_sub_ps(ay, b.y);
  const __m128 dz = _mm_sub_ps(az, b.z);
  return _mm_add_ps(_mm_add_ps(mul(dx, dx), mul(dy, dy)), mul(dz, dz));
}

/// linked[i] = bit i of a `_mm_movemask_ps` result, for i < 4. O(1).
STREAMCLUST_ALWAYS_INLINE void store_four_decisions(int bits, std::uint8_t* linked) {
  linked[0] = static_cast<std::uint8_t>(bits & 1);
  linked[1] = static_cast<std::uint8_t>((bits >> 1) & 1);
  linked[2] = static_cast<std::uint8_t>((bits >> 2) & 1);
  linked[3] = static_cast<std::uint8_t>((bits >> 3) & 1);
}
#endif

}  // namespace streamclust::detail
