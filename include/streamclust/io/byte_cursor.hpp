// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Bounds-checked reading of little-endian binary structures from memory:
/// every read names what it wanted, and running off the end is an InputError
/// that says where (file and offset) and what was expected.

#include <streamclust/io/error.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

namespace streamclust::io::detail {

/// Where a buffer came from, for error messages: the file, and how an offset
/// in the buffer is written ("byte " + (base + offset) for a buffer read at
/// file offset `base`; a decompressed chunk says so in its prefix).
struct BufferOrigin {
  std::string file;
  std::string prefix = "byte ";
  std::uint64_t base = 0;

  std::string where(std::size_t offset) const { return prefix + std::to_string(base + offset); }
};

/// A read position in `size` bytes at `data` (not owned). Reads advance the
/// position; a read past the end throws InputError naming `what` and the
/// bytes needed and left. O(1) per scalar; not thread-safe.
class ByteCursor {
 public:
  ByteCursor(const std::uint8_t* data, std::size_t size, const BufferOrigin& origin) noexcept
      : data_(data), size_(size), origin_(&origin) {}

  std::size_t position() const noexcept { return pos_; }
  std::size_t size() const noexcept { return size_; }
  std::size_t remaining() const noexcept { return size_ - pos_; }
  bool at_end() const noexcept { return pos_ == size_; }
  const std::uint8_t* data() const noexcept { return data_; }
  const BufferOrigin& origin() const noexcept { return *origin_; }

  /// A little-endian arithmetic value.
  template <class T>
  T le(const char* what) {
    static_assert(std::is_arithmetic_v<T>, "ByteCursor::le reads arithmetic types");
    const std::uint8_t* p = bytes(sizeof(T), what);
    T v;
    if constexpr (sizeof(T) == 1) {
      std::memcpy(&v, p, 1);
    } else {
      using U = std::conditional_t<sizeof(T) == 2, std::uint16_t,
                                   std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>;
      U u = 0;
      for (std::size_t i = 0; i < sizeof(T); ++i) u = static_cast<U>(u | (static_cast<U>(p[i]) << (8 * i)));
      std::memcpy(&v, &u, sizeof(T));
    }
    return v;
  }
  std::uint8_t u8(const char* what) { return le<std::uint8_t>(what); }
  std::uint16_t u16(const char* what) { return le<std::uint16_t>(what); }
  std::uint32_t u32(const char* what) { return le<std::uint32_t>(what); }
  std::uint64_t u64(const char* what) { return le<std::uint64_t>(what); }

  /// `n` bytes; returns their address and advances.
  const std::uint8_t* bytes(std::uint64_t n, const char* what) {
    if (n > remaining()) {
      fail(std::string("truncated ") + what + ": expected " + std::to_string(n) + " bytes, " +
           std::to_string(remaining()) + " left");
    }
    const std::uint8_t* p = data_ + pos_;
    pos_ += static_cast<std::size_t>(n);
    return p;
  }

  /// A string with a uint32 length prefix (MCAP, ROS 1).
  std::string_view string32(const char* what) {
    const std::uint32_t n = u32(what);
    return {reinterpret_cast<const char*>(bytes(n, what)), n};
  }

  void skip(std::uint64_t n, const char* what) { bytes(n, what); }
  void seek(std::size_t position) noexcept { pos_ = position <= size_ ? position : size_; }

  /// Throws InputError at the current position.
  [[noreturn]] void fail(std::string what) const { fail_at(pos_, std::move(what)); }
  /// Throws InputError at buffer offset `offset`.
  [[noreturn]] void fail_at(std::size_t offset, std::string what) const {
    throw InputError(origin_->file, origin_->where(offset), std::move(what));
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  const BufferOrigin* origin_;
};

}  // namespace streamclust::io::detail
