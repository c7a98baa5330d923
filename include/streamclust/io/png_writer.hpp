// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A PNG writer: 8-bit RGB images, the scanlines compressed by zlib (Debian's
/// zlib1g) into one IDAT chunk, CRC-32 per chunk, as the PNG specification
/// (ISO/IEC 15948) defines them. A bird's-eye picture, mostly background,
/// compresses to a few percent of its 3 x width x height bytes.

#include <streamclust/io/crc32.hpp>

#include <zlib.h>

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
/// interlace), one IDAT (the zlib stream, level 6, of the rows, each row
/// preceded by filter type 0), IEND. O(width x height); allocates about twice
/// the image's size. Throws std::runtime_error when zlib fails (out of memory).
inline std::vector<std::uint8_t> encode_png(const RgbImage& image) {
  const std::size_t row_bytes = image.width() * 3;
  std::vector<std::uint8_t> raw;  // filtered scanlines
  raw.reserve((row_bytes + 1) * image.height());
  for (std::size_t y = 0; y < image.height(); ++y) {
    raw.push_back(0);  // filter: none (sparse pictures compress best unfiltered)
    const auto row = image.pixels().begin() + static_cast<std::ptrdiff_t>(y * row_bytes);
    raw.insert(raw.end(), row, row + static_cast<std::ptrdiff_t>(row_bytes));
  }

  // The image is at most 65535 x 65535 x 3 bytes, above uLong's 32 bits on
  // some platforms: compress in steps through a z_stream.
  std::vector<std::uint8_t> zlib(raw.size() / 16 + 1024);  // grows by doubling
  z_stream z{};
  if (deflateInit(&z, 6) != Z_OK) throw std::runtime_error("PNG writer: zlib deflateInit failed");
  std::size_t consumed = 0;
  int status = Z_OK;
  while (status != Z_STREAM_END) {
    constexpr std::size_t kStep = std::size_t{1} << 30;  // bytes per call, fits uInt
    if (z.avail_in == 0 && consumed < raw.size()) {
      const std::size_t n = std::min(kStep, raw.size() - consumed);
      z.next_in = raw.data() + consumed;
      z.avail_in = static_cast<uInt>(n);
      consumed += n;
    }
    if (z.total_out == zlib.size()) zlib.resize(zlib.size() * 2);
    const std::size_t written = zlib.size() - static_cast<std::size_t>(z.total_out);
    z.next_out = zlib.data() + z.total_out;
    z.avail_out = static_cast<uInt>(std::min(kStep, written));
    status = deflate(&z, consumed == raw.size() ? Z_FINISH : Z_NO_FLUSH);
    if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR) {
      deflateEnd(&z);
      throw std::runtime_error("PNG writer: zlib deflate failed (" + std::to_string(status) + ")");
    }
  }
  zlib.resize(static_cast<std::size_t>(z.total_out));
  deflateEnd(&z);

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
