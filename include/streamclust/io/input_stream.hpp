// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Internals shared by the readers: a buffered byte source that knows its
/// offset, a bounded line reader, number parsing and field-name lookup.

#include <streamclust/io/error.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#if defined(__BYTE_ORDER__) && defined(__ORDER_LITTLE_ENDIAN__) && (__BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__)
#error "STREAMCLUST_IO_LITTLE_ENDIAN_ONLY: the binary readers and writers assume a little-endian host"
#endif

namespace streamclust::io::detail {

/// Longest text line a reader accepts (CSV, PCD/PLY ascii data) [bytes].
inline constexpr std::size_t max_line_bytes = std::size_t{1} << 20;
/// Longest header line (PCD, PLY) [bytes], and most header lines.
inline constexpr std::size_t max_header_line_bytes = std::size_t{1} << 16;
inline constexpr std::size_t max_header_lines = 10000;

inline std::string where_line(std::uint64_t line) { return "line " + std::to_string(line); }
inline std::string where_byte(std::uint64_t byte) { return "byte " + std::to_string(byte); }

/// `s` with every byte outside printable ASCII (control bytes, DEL, non-ASCII,
/// also '"' and '\\') written as \xNN, cut after `limit` bytes ("..."): file
/// content is quoted in messages only through this. O(min(|s|, limit)).
inline std::string printable(std::string_view s, std::size_t limit = 40) {
  static const char* hex = "0123456789abcdef";
  std::string r;
  for (std::size_t i = 0; i < s.size() && i < limit; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 32 && c < 127 && c != '"' && c != '\\') {
      r += static_cast<char>(c);
    } else {
      r += "\\x";
      r += hex[c >> 4];
      r += hex[c & 15];
    }
  }
  if (s.size() > limit) r += "...";
  return r;
}

/// A short, printable, quoted excerpt of `s` for error messages.
inline std::string quoted(std::string_view s) { return '"' + printable(s) + '"'; }

/// "line N, column K (name)", the name from the file made printable.
inline std::string where_column(std::uint64_t line, std::size_t column, std::string_view name) {
  return "line " + std::to_string(line) + ", column " + std::to_string(column) + " (" + printable(name) + ")";
}

inline bool is_space(char c) noexcept { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

inline std::string_view trim(std::string_view s) noexcept {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

inline std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

/// Splits on runs of blanks (space, tab, CR).
inline void split_blanks(std::string_view s, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_space(s[i])) ++i;
    const std::size_t b = i;
    while (i < s.size() && !is_space(s[i])) ++i;
    if (i > b) out.push_back(s.substr(b, i - b));
  }
}

/// Parses a whole (trimmed) token as a floating-point number: decimal or
/// exponent notation, optional sign, "nan", "inf". False on anything else,
/// including an empty token and values out of the type's range.
template <class T>
bool parse_real(std::string_view s, T& value) noexcept {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty() || s.front() == '+') return false;
  const char* first = s.data();
  const char* last = s.data() + s.size();
  const auto r = std::from_chars(first, last, value, std::chars_format::general);
  return r.ec == std::errc() && r.ptr == last;
}

/// Parses an integer token; also accepts an integral floating-point value
/// ("3.0", "1e3") within the int64 range.
inline bool parse_int64(std::string_view s, std::int64_t& value) noexcept {
  std::string_view u = s;
  if (!u.empty() && u.front() == '+') u.remove_prefix(1);
  if (!u.empty()) {
    const auto r = std::from_chars(u.data(), u.data() + u.size(), value);
    if (r.ec == std::errc() && r.ptr == u.data() + u.size()) return true;
  }
  double d = 0;
  if (!parse_real(s, d)) return false;
  if (!(d >= -9.2e18 && d <= 9.2e18) || d != static_cast<double>(static_cast<std::int64_t>(d))) return false;
  value = static_cast<std::int64_t>(d);
  return true;
}

/// Parses an unsigned decimal integer (header values); false on overflow.
inline bool parse_uint64(std::string_view s, std::uint64_t& value) noexcept {
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), value);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

/// double -> float without undefined behaviour: out-of-range values become +-inf.
inline float to_float(double v) noexcept {
  if (v > static_cast<double>(std::numeric_limits<float>::max())) return std::numeric_limits<float>::infinity();
  if (v < -static_cast<double>(std::numeric_limits<float>::max())) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(v);
}

/// double -> label: non-finite values give -1, others are truncated and clamped to int64.
inline std::int64_t to_label(double v) noexcept {
  if (!(v == v) || v == std::numeric_limits<double>::infinity() || v == -std::numeric_limits<double>::infinity())
    return -1;
  if (v >= 9.2e18) return std::numeric_limits<std::int64_t>::max();
  if (v <= -9.2e18) return std::numeric_limits<std::int64_t>::min();
  return static_cast<std::int64_t>(v);
}

/// Scalar types of binary PCD / PLY fields.
enum class Scalar : unsigned char { i8, u8, i16, u16, i32, u32, i64, u64, f32, f64 };

inline std::size_t scalar_size(Scalar s) noexcept {
  switch (s) {
    case Scalar::i8: case Scalar::u8: return 1;
    case Scalar::i16: case Scalar::u16: return 2;
    case Scalar::i32: case Scalar::u32: case Scalar::f32: return 4;
    case Scalar::i64: case Scalar::u64: case Scalar::f64: return 8;
  }
  return 1;
}

inline bool scalar_is_float(Scalar s) noexcept { return s == Scalar::f32 || s == Scalar::f64; }

template <class T>
T load_le(const unsigned char* p) noexcept {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// Writes `v` little-endian at p (the supported targets are little-endian).
template <class T>
void store_le(unsigned char* p, T v) noexcept {
  std::memcpy(p, &v, sizeof v);
}

/// The little-endian value at p as a double.
inline double scalar_to_double(Scalar s, const unsigned char* p) noexcept {
  switch (s) {
    case Scalar::i8: return load_le<std::int8_t>(p);
    case Scalar::u8: return load_le<std::uint8_t>(p);
    case Scalar::i16: return load_le<std::int16_t>(p);
    case Scalar::u16: return load_le<std::uint16_t>(p);
    case Scalar::i32: return load_le<std::int32_t>(p);
    case Scalar::u32: return load_le<std::uint32_t>(p);
    case Scalar::i64: return static_cast<double>(load_le<std::int64_t>(p));
    case Scalar::u64: return static_cast<double>(load_le<std::uint64_t>(p));
    case Scalar::f32: return load_le<float>(p);
    case Scalar::f64: return load_le<double>(p);
  }
  return 0;
}

/// The little-endian value at p as a float (out-of-range doubles become +-inf).
inline float scalar_to_float(Scalar s, const unsigned char* p) noexcept {
  if (s == Scalar::f32) return load_le<float>(p);
  return to_float(scalar_to_double(s, p));
}

/// The little-endian value at p as a label (integers exact, clamped to int64;
/// non-finite floats give -1).
inline std::int64_t scalar_to_label(Scalar s, const unsigned char* p) noexcept {
  switch (s) {
    case Scalar::i64: return load_le<std::int64_t>(p);
    case Scalar::u64: {
      const auto v = load_le<std::uint64_t>(p);
      return v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())
                 ? std::numeric_limits<std::int64_t>::max()
                 : static_cast<std::int64_t>(v);
    }
    case Scalar::f32: case Scalar::f64: return to_label(scalar_to_double(s, p));
    default: return static_cast<std::int64_t>(scalar_to_double(s, p));
  }
}

/// A file read through a fixed buffer (64 KiB), tracking the absolute offset
/// of the next unread byte. Memory is bounded by the buffer plus one line.
class ByteSource {
 public:
  enum class LineStatus { ok, eof, too_long };

  /// Opens `path`; throws InputError "cannot open" when it cannot.
  explicit ByteSource(const std::string& path) : path_(path), buf_(std::size_t{1} << 16) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
      throw InputError(path, "byte 0", "cannot open: is a directory");
    in_.open(path, std::ios::binary);
    if (!in_) throw InputError(path, "byte 0", "cannot open: no such file or not readable");
    const auto sz = std::filesystem::file_size(path, ec);
    size_ = ec ? std::numeric_limits<std::uint64_t>::max() : static_cast<std::uint64_t>(sz);
  }

  const std::string& path() const noexcept { return path_; }
  /// File size in bytes (UINT64_MAX when unknown, e.g. a pipe).
  std::uint64_t size() const noexcept { return size_; }
  /// Absolute offset of the next unread byte.
  std::uint64_t offset() const noexcept { return base_ + pos_; }
  /// Bytes left after offset() according to the file size.
  std::uint64_t remaining() const noexcept { return size_ >= offset() ? size_ - offset() : 0; }

  /// Reads one line (without '\n' and a trailing '\r') into `line`.
  /// `eof`: no byte left. `too_long`: more than `max_len` bytes without a newline.
  LineStatus read_line(std::string& line, std::size_t max_len) {
    line.clear();
    bool any = false;
    for (;;) {
      if (pos_ == end_ && !fill()) {
        if (!any) return LineStatus::eof;
        break;
      }
      any = true;
      const char* b = buf_.data() + pos_;
      const auto* nl = static_cast<const char*>(std::memchr(b, '\n', end_ - pos_));
      const std::size_t n = nl ? static_cast<std::size_t>(nl - b) : end_ - pos_;
      if (line.size() + n > max_len) return LineStatus::too_long;
      line.append(b, n);
      pos_ += n;
      if (nl) {
        ++pos_;
        break;
      }
    }
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return LineStatus::ok;
  }

  /// Copies up to n bytes into dst; returns how many (fewer only at end of file).
  std::size_t read(char* dst, std::size_t n) {
    std::size_t done = 0;
    while (done < n) {
      if (pos_ == end_) {
        // Large reads bypass the buffer.
        if (n - done >= buf_.size()) {
          base_ += end_;
          pos_ = end_ = 0;
          if (!in_) break;
          in_.read(dst + done, static_cast<std::streamsize>(n - done));
          const auto got = static_cast<std::size_t>(in_.gcount());
          base_ += got;
          done += got;
          if (got == 0) break;
          continue;
        }
        if (!fill()) break;
      }
      const std::size_t k = std::min(n - done, end_ - pos_);
      std::memcpy(dst + done, buf_.data() + pos_, k);
      pos_ += k;
      done += k;
    }
    return done;
  }

  /// Skips up to n bytes; returns how many.
  std::uint64_t skip(std::uint64_t n) {
    char tmp[4096];
    std::uint64_t done = 0;
    while (done < n) {
      const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(n - done, sizeof tmp));
      const std::size_t got = read(tmp, want);
      done += got;
      if (got < want) break;
    }
    return done;
  }

  /// True when no byte is left (reads ahead to know).
  bool at_end() { return pos_ == end_ && !fill(); }

  /// Peeks at up to n bytes at the current position without consuming them
  /// (only valid right after opening).
  std::string peek(std::size_t n) {
    if (pos_ == end_) fill();
    return std::string(buf_.data() + pos_, std::min(n, end_ - pos_));
  }

 private:
  bool fill() {
    base_ += end_;
    pos_ = end_ = 0;
    if (!in_) return false;
    in_.read(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    end_ = static_cast<std::size_t>(in_.gcount());
    return end_ > 0;
  }

  std::string path_;
  std::ifstream in_;
  std::vector<char> buf_;
  std::size_t pos_ = 0;    // next unread byte in buf_
  std::size_t end_ = 0;    // valid bytes in buf_
  std::uint64_t base_ = 0; // file offset of buf_[0]
  std::uint64_t size_ = 0;
};

}  // namespace streamclust::io::detail
