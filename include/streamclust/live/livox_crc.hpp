// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The CRCs of the Livox network protocols (parameters in CRC-catalogue terms;
/// "check" is the CRC of the nine bytes "123456789"):
///
/// | function            | protocol, use                          | poly   | refin/out | init   | xorout | check      |
/// |---------------------|----------------------------------------|--------|-----------|--------|--------|------------|
/// | crc16_ccitt_false   | SDK2 control header                    | 0x1021 | no        | 0xFFFF | 0      | 0x29B1     |
/// | crc32_iso_hdlc      | SDK2 control data, data packets        | 0x04C11DB7 | yes   | 0xFFFFFFFF | 0xFFFFFFFF | 0xCBF43926 |
/// | crc16_livox_sdk1    | SDK1 control preamble                  | 0x1021 | yes       | 0x4C49 | 0      | 0xAB4E     |
/// | crc32_livox_sdk1    | SDK1 control frame                     | 0x04C11DB7 | yes   | register 0xA9B0A7F5 | 0xFFFFFFFF | 0xB08DB5B1 |
///
/// Sources: Livox wiki "CRC Algorithm" (SDK2); the seeds 0x4C49 and 0x564F580A
/// of `Livox-SDK/Livox-SDK:sdk_core/src/comm/comm_port.cpp` (SDK1), whose
/// CRC-32 XORs its seed with 0xFFFFFFFF before the first byte.
///
/// All functions are pure, O(n), thread-safe.

#include <streamclust/io/crc32.hpp>

#include <array>
#include <cstddef>
#include <cstdint>

namespace streamclust::live {

namespace detail {

/// Table of the non-reflected CRC-16 with polynomial 0x1021.
inline const std::array<std::uint16_t, 256>& crc16_msb_table() noexcept {
  static const std::array<std::uint16_t, 256> table = [] {
    std::array<std::uint16_t, 256> t{};
    for (unsigned i = 0; i < 256; ++i) {
      auto c = static_cast<std::uint16_t>(i << 8);
      for (int k = 0; k < 8; ++k) c = static_cast<std::uint16_t>((c & 0x8000u) ? (c << 1) ^ 0x1021u : c << 1);
      t[i] = c;
    }
    return t;
  }();
  return table;
}

/// Table of the reflected CRC-16 with polynomial 0x1021 (0x8408 reflected).
inline const std::array<std::uint16_t, 256>& crc16_lsb_table() noexcept {
  static const std::array<std::uint16_t, 256> table = [] {
    std::array<std::uint16_t, 256> t{};
    for (unsigned i = 0; i < 256; ++i) {
      auto c = static_cast<std::uint16_t>(i);
      for (int k = 0; k < 8; ++k) c = static_cast<std::uint16_t>((c & 1u) ? (c >> 1) ^ 0x8408u : c >> 1);
      t[i] = c;
    }
    return t;
  }();
  return table;
}

}  // namespace detail

/// CRC-16/CCITT-FALSE of `n` bytes (SDK2 control frames, header bytes [0, 18)).
inline std::uint16_t crc16_ccitt_false(const std::uint8_t* data, std::size_t n) noexcept {
  const auto& table = detail::crc16_msb_table();
  std::uint16_t crc = 0xFFFFu;
  for (std::size_t i = 0; i < n; ++i)
    crc = static_cast<std::uint16_t>((crc << 8) ^ table[((crc >> 8) ^ data[i]) & 0xFFu]);
  return crc;
}

/// CRC-32/ISO-HDLC of `n` bytes (SDK2 control data and data packets).
inline std::uint32_t crc32_iso_hdlc(const std::uint8_t* data, std::size_t n) noexcept {
  return io::detail::crc32(data, n);
}

/// CRC-16 of SDK1 control preambles: MCRF4XX with the Livox seed 0x4C49.
/// Over a preamble that ends with its own CRC (little-endian) it gives 0.
inline std::uint16_t crc16_livox_sdk1(const std::uint8_t* data, std::size_t n) noexcept {
  const auto& table = detail::crc16_lsb_table();
  std::uint16_t crc = 0x4C49u;
  for (std::size_t i = 0; i < n; ++i) crc = static_cast<std::uint16_t>((crc >> 8) ^ table[(crc ^ data[i]) & 0xFFu]);
  return crc;
}

/// CRC-32 of SDK1 control frames: the reflected CRC-32 with the Livox seed
/// 0x564F580A (the CRC of no bytes).
inline std::uint32_t crc32_livox_sdk1(const std::uint8_t* data, std::size_t n) noexcept {
  return io::detail::crc32(data, n, 0x564F580Au);
}

}  // namespace streamclust::live
