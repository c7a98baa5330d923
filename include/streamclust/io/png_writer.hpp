// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A PNG writer with no dependency: 8-bit RGB images, stored (uncompressed)
/// deflate blocks inside the zlib stream, CRC-32 per chunk and Adler-32 over
/// the image data, as the PNG specification (ISO/IEC 15948) and RFC 1950 /
/// 1951 define them. Any PNG reader opens the result; it is about
/// 3 x width x height bytes (no compression).

#include <streamclust/io/crc32.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::io {

/// An 8-bit RGB image, row-major from the top-left corner, 3 bytes per pixel.
/// Plain value type; not thread-safe for concurrent writes.
class RgbImage {
 public:
  using Color = std::array<std::uint8_t, 3>;

  /// A `width` x `height` image filled with `background`. Throws
  /// std::invalid_argument when a side is 0 or above 65535.
  RgbImage(std::size_t width, std::size_t height, Color background = {0, 0, 0}) : width_(width), height_(height) {
    if (width == 0 || height == 0 || width > 65535 || height > 65535) {
      throw std::invalid_argument("RgbImage: width and height must be in [1, 65535], got " + std::to_string(width) +
                                  " x " + std::to_string(height));
    }
    pixels_.resize(width * height * 3);
    for (std::size_t i = 0; i < width * height; ++i) {
      pixels_[3 * i] = background[0];
      pixels_[3 * i + 1] = background[1];
      pixels_[3 * i + 2] = background[2];
    }
  }

  std::size_t width() const noexcept { return width_; }
  std::size_t height() const noexcept { return height_; }

  /// Sets pixel (x, y) (x to the right, y down); a pixel outside is ignored. O(1).
  void set(long x, long y, Color c) noexcept {
    if (x < 0 || y < 0 || static_cast<std::size_t>(x) >= width_ || static_cast<std::size_t>(y) >= height_) return;
    std::uint8_t* p = &pixels_[(static_cast<std::size_t>(y) * width_ + static_cast<std::size_t>(x)) * 3];
    p[0] = c[0];
    p[1] = c[1];
    p[2] = c[2];
  }

  /// Pixel (x, y); precondition: inside the image.
  Color at(std::size_t x, std::size_t y) const noexcept {
    const std::uint8_t* p = &pixels_[(y * width_ + x) * 3];
    return {p[0], p[1], p[2]};
  }

  /// The pixels, row-major, RGB.
  const std::vector<std::uint8_t>& pixels() const noexcept { return pixels_; }

 private:
  std::size_t width_;
  std::size_t height_;
  std::vector<std::uint8_t> pixels_;
};

namespace detail {

/// Adler-32 (RFC 1950) of `n` bytes. O(n).
inline std::uint32_t adler32(const std::uint8_t* data, std::size_t n) noexcept {
  constexpr std::uint32_t kMod = 65521;
  std::uint32_t a = 1;
  std::uint32_t b = 0;
  for (std::size_t i = 0; i < n; ++i) {
    a = (a + data[i]) % kMod;
    b = (b + a) % kMod;
  }
  return (b << 16) | a;
}

inline void put_be32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 24));
  out.push_back(static_cast<std::uint8_t>(v >> 16));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v));
}

/// Appends one chunk: length, type, data, CRC-32 of type and data.
inline void put_chunk(std::vector<std::uint8_t>& out, const char (&type)[5], const std::vector<std::uint8_t>& data) {
  put_be32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t type_at = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put_be32(out, crc32(out.data() + type_at, 4 + data.size()));
}

}  // namespace detail

/// The bytes of a PNG file holding `image`: signature, IHDR (8-bit RGB, no
/// interlace), one IDAT (a zlib stream of stored deflate blocks of at most
/// 65535 bytes over the rows, each row preceded by filter type 0), IEND.
/// O(width x height); allocates about twice the image's size.
inline std::vector<std::uint8_t> encode_png(const RgbImage& image) {
  const std::size_t row_bytes = image.width() * 3;
  std::vector<std::uint8_t> raw;  // filtered scanlines
  raw.reserve((row_bytes + 1) * image.height());
  for (std::size_t y = 0; y < image.height(); ++y) {
    raw.push_back(0);  // filter: none
    const auto row = image.pixels().begin() + static_cast<std::ptrdiff_t>(y * row_bytes);
    raw.insert(raw.end(), row, row + static_cast<std::ptrdiff_t>(row_bytes));
  }

  std::vector<std::uint8_t> zlib;
  constexpr std::size_t kMaxStored = 65535;
  zlib.reserve(raw.size() + 6 + 5 * (raw.size() / kMaxStored + 1));
  zlib.push_back(0x78);  // CMF: deflate, 32 KiB window
  zlib.push_back(0x01);  // FLG: no dictionary, fastest; (0x78 << 8 | 0x01) % 31 == 0
  std::size_t pos = 0;
  do {
    const std::size_t n = std::min(kMaxStored, raw.size() - pos);
    const bool last = pos + n == raw.size();
    zlib.push_back(last ? 1 : 0);  // BFINAL, BTYPE = 00 (stored)
    zlib.push_back(static_cast<std::uint8_t>(n & 0xFFu));
    zlib.push_back(static_cast<std::uint8_t>(n >> 8));
    zlib.push_back(static_cast<std::uint8_t>(~n & 0xFFu));
    zlib.push_back(static_cast<std::uint8_t>((~n >> 8) & 0xFFu));
    zlib.insert(zlib.end(), raw.begin() + static_cast<std::ptrdiff_t>(pos),
                raw.begin() + static_cast<std::ptrdiff_t>(pos + n));
    pos += n;
  } while (pos < raw.size());
  detail::put_be32(zlib, detail::adler32(raw.data(), raw.size()));

  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> ihdr;
  detail::put_be32(ihdr, static_cast<std::uint32_t>(image.width()));
  detail::put_be32(ihdr, static_cast<std::uint32_t>(image.height()));
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // bit depth 8, colour type 2 (RGB), deflate, filter 0, no interlace
  detail::put_chunk(png, "IHDR", ihdr);
  detail::put_chunk(png, "IDAT", zlib);
  detail::put_chunk(png, "IEND", {});
  return png;
}

/// Writes `image` as a PNG file at `path`. Throws std::runtime_error naming
/// the file when it cannot be written.
inline void write_png(const std::string& path, const RgbImage& image) {
  const std::vector<std::uint8_t> bytes = encode_png(image);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw std::runtime_error(path + ": write failed (disk full?)");
}

}  // namespace streamclust::io
