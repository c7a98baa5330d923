// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// CRC-32 as PNG chunks, zlib and MCAP use it (ISO 3309 / ITU-T V.42,
/// polynomial 0xEDB88320 reflected, initial value and final XOR 0xFFFFFFFF).

#include <array>
#include <cstddef>
#include <cstdint>

namespace streamclust::io::detail {

/// CRC-32 of `n` bytes; `crc` continues a running value (start with 0), so
/// `crc32(b, nb, crc32(a, na))` is the CRC of a followed by b. O(n),
/// table-driven; thread-safe (the table is built once, thread-safely).
inline std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc = 0) noexcept {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

}  // namespace streamclust::io::detail
