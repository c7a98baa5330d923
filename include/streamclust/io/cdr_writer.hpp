// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Serializing ROS 2 messages in CDR (XCDR1, little-endian), the encoding
/// MCAP's `ros2` profile and Foxglove expect: the 4-byte encapsulation header
/// `00 01 00 00`, every primitive aligned to its size (at most 8) from the
/// end of that header, strings as a uint32 length that counts the
/// terminating NUL, sequences as a uint32 count. The inverse of
/// ros/message_decoder.hpp for the CDR encoding.
///
///     streamclust::io::CdrWriter w;
///     w.u32(sec); w.u32(nanosec); w.string("lidar");
///     const std::vector<std::uint8_t>& bytes = w.bytes();

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

namespace streamclust::io {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "STREAMCLUST_CDR_WRITER_LITTLE_ENDIAN: CdrWriter copies values in host order and writes CDR_LE");

/// A growing CDR message. O(1) amortized per value; not thread-safe.
class CdrWriter {
 public:
  CdrWriter() { buffer_ = {0x00, 0x01, 0x00, 0x00}; }

  void boolean(bool v) { u8(v ? 1 : 0); }
  void u8(std::uint8_t v) { buffer_.push_back(v); }
  void u16(std::uint16_t v) { put(v); }
  void u32(std::uint32_t v) { put(v); }
  void i32(std::int32_t v) { put(v); }
  void u64(std::uint64_t v) { put(v); }
  void f32(float v) { put(v); }
  void f64(double v) { put(v); }

  void string(std::string_view s) {
    u32(static_cast<std::uint32_t>(s.size() + 1));
    buffer_.insert(buffer_.end(), s.begin(), s.end());
    buffer_.push_back(0);
  }
  /// A sequence's element count; the elements follow.
  void count(std::size_t n) { u32(static_cast<std::uint32_t>(n)); }
  /// A uint8[] sequence.
  void bytes(const std::uint8_t* p, std::size_t n) {
    count(n);
    buffer_.insert(buffer_.end(), p, p + n);
  }

  const std::vector<std::uint8_t>& bytes() const noexcept { return buffer_; }
  /// Starts a new message, keeping the capacity.
  void clear() { buffer_.resize(4); }

 private:
  template <class T>
  void put(T v) {
    const std::size_t rel = buffer_.size() - 4;
    buffer_.resize(buffer_.size() + (sizeof(T) - rel % sizeof(T)) % sizeof(T), 0);
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));  // little-endian hosts (x86-64, AArch64)
    buffer_.insert(buffer_.end(), b, b + sizeof(T));
  }

  std::vector<std::uint8_t> buffer_;
};

}  // namespace streamclust::io
