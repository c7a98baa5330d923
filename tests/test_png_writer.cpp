// SPDX-License-Identifier: MIT
// The PNG writer (<streamclust/io/png_writer.hpp>), checked by a decoder
// written here: signature, chunk order and lengths, CRC-32 of every chunk (bit
// by bit, no table), IHDR fields, the zlib header, the stream inflated by
// zlib, Adler-32 (computed here), the filter bytes and every pixel.

#include <doctest/doctest.h>

#include <streamclust/io/png_writer.hpp>

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "support/temp_dir.hpp"

namespace io = streamclust::io;
using Bytes = std::vector<std::uint8_t>;

namespace {

std::uint32_t be32(const Bytes& b, std::size_t at) {
  if (at + 4 > b.size()) throw std::runtime_error("truncated at byte " + std::to_string(at));
  return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) | (std::uint32_t{b[at + 2]} << 8) |
         std::uint32_t{b[at + 3]};
}

/// CRC-32 bit by bit (the definition, not the writer's table).
std::uint32_t reference_crc(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return c ^ 0xFFFFFFFFu;
}

std::uint32_t reference_adler(const Bytes& d) {
  std::uint64_t a = 1;
  std::uint64_t b = 0;
  for (const std::uint8_t x : d) {
    a = (a + x) % 65521;
    b = (b + a) % 65521;
  }
  return static_cast<std::uint32_t>((b << 16) | a);
}

struct DecodedPng {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  Bytes rgb;
};

/// Decodes what the writer produces (8-bit RGB, one zlib stream, filter 0);
/// throws std::runtime_error on anything else or on any inconsistency.
DecodedPng decode(const Bytes& png) {
  const Bytes signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (png.size() < 8 || !std::equal(signature.begin(), signature.end(), png.begin()))
    throw std::runtime_error("bad signature");
  std::vector<std::string> types;
  Bytes idat;
  DecodedPng out;
  std::size_t at = 8;
  while (at < png.size()) {
    const std::uint32_t length = be32(png, at);
    if (at + 12 + length > png.size()) throw std::runtime_error("chunk runs past the end");
    const std::string type(png.begin() + static_cast<std::ptrdiff_t>(at + 4), png.begin() + static_cast<std::ptrdiff_t>(at + 8));
    if (reference_crc(png.data() + at + 4, 4 + length) != be32(png, at + 8 + length))
      throw std::runtime_error("CRC mismatch in " + type);
    const Bytes data(png.begin() + static_cast<std::ptrdiff_t>(at + 8), png.begin() + static_cast<std::ptrdiff_t>(at + 8 + length));
    types.push_back(type);
    if (type == "IHDR") {
      if (length != 13) throw std::runtime_error("IHDR length");
      out.width = be32(data, 0);
      out.height = be32(data, 4);
      if (data[8] != 8 || data[9] != 2 || data[10] != 0 || data[11] != 0 || data[12] != 0)
        throw std::runtime_error("IHDR: not 8-bit RGB, deflate, filter 0, no interlace");
    } else if (type == "IDAT") {
      idat.insert(idat.end(), data.begin(), data.end());
    }
    at += 12 + length;
  }
  if (types.size() < 3 || types.front() != "IHDR" || types.back() != "IEND") throw std::runtime_error("chunk order");

  // zlib: CMF/FLG, the deflate stream, Adler-32.
  if (idat.size() < 6 || (idat[0] & 0x0F) != 8 || ((idat[0] << 8) | idat[1]) % 31 != 0 || (idat[1] & 0x20) != 0)
    throw std::runtime_error("zlib header");
  Bytes raw((std::size_t{out.width} * 3 + 1) * out.height);
  z_stream z{};
  if (inflateInit(&z) != Z_OK) throw std::runtime_error("inflateInit");
  z.next_in = idat.data();
  z.avail_in = static_cast<uInt>(idat.size());
  z.next_out = raw.data();
  z.avail_out = static_cast<uInt>(raw.size());
  const int status = inflate(&z, Z_FINISH);
  const std::size_t used = idat.size() - z.avail_in;
  const std::size_t produced = raw.size() - z.avail_out;
  inflateEnd(&z);
  if (status != Z_STREAM_END) throw std::runtime_error("inflate: " + std::to_string(status));
  if (used != idat.size()) throw std::runtime_error("bytes after the zlib stream");
  if (produced != raw.size()) throw std::runtime_error("image data size");
  if (be32(idat, idat.size() - 4) != reference_adler(raw)) throw std::runtime_error("Adler-32 mismatch");

  const std::size_t row = std::size_t{out.width} * 3;
  if (raw.size() != (row + 1) * out.height) throw std::runtime_error("image data size");
  for (std::size_t y = 0; y < out.height; ++y) {
    if (raw[y * (row + 1)] != 0) throw std::runtime_error("filter type");
    out.rgb.insert(out.rgb.end(), raw.begin() + static_cast<std::ptrdiff_t>(y * (row + 1) + 1),
                   raw.begin() + static_cast<std::ptrdiff_t>((y + 1) * (row + 1)));
  }
  return out;
}

io::RgbImage pattern(std::size_t w, std::size_t h) {
  io::RgbImage img(w, h, {10, 20, 30});
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; x += 3)
      img.set(static_cast<long>(x), static_cast<long>(y),
              {static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y), static_cast<std::uint8_t>(x ^ y)});
  return img;
}

}  // namespace

TEST_CASE("PNG writer: CRC-32 (writer) and Adler-32 (test decoder) of known strings") {
  const std::string s = "123456789";
  const auto* p = reinterpret_cast<const std::uint8_t*>(s.data());
  CHECK(io::detail::crc32(p, s.size()) == 0xCBF43926u);  // the CRC-32 check value
  CHECK(reference_adler(Bytes(p, p + s.size())) == 0x091E01DEu);  // the decoder's own check
  const std::string iend = "IEND";
  CHECK(io::detail::crc32(reinterpret_cast<const std::uint8_t*>(iend.data()), 4) == 0xAE426082u);
}

TEST_CASE("PNG writer: decodes to the same pixels, small and larger images") {
  for (const auto& size : {std::pair<std::size_t, std::size_t>{1, 1}, {7, 3}, {300, 200}}) {
    const std::size_t w = size.first;  // not a structured binding: INFO captures it (clang 14, C++17)
    const std::size_t h = size.second;
    INFO(w << " x " << h);
    const io::RgbImage img = pattern(w, h);
    const DecodedPng d = decode(io::encode_png(img));
    CHECK(d.width == w);
    CHECK(d.height == h);
    CHECK(d.rgb == img.pixels());
  }
}

TEST_CASE("PNG writer: a sparse picture compresses to a few percent of its pixels") {
  // A bird's-eye picture is mostly background: 900 x 560 with a point every
  // 7 pixels in both directions holds 1.5 MB of pixels.
  io::RgbImage img(900, 560, {20, 20, 24});
  for (long y = 0; y < 560; y += 7)
    for (long x = 0; x < 900; x += 7) img.set(x, y, {static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y), 200});
  const Bytes png = io::encode_png(img);
  CHECK(png.size() < img.pixels().size() / 20);
  CHECK(decode(png).rgb == img.pixels());
}

TEST_CASE("PNG writer: the decoder rejects a flipped bit (the checks can fail)") {
  const Bytes good = io::encode_png(pattern(20, 10));
  REQUIRE_NOTHROW(decode(good));
  Bytes pixel = good;
  pixel[pixel.size() - 40] ^= 0x01;  // inside IDAT: CRC mismatch
  CHECK_THROWS_WITH_AS(decode(pixel), "CRC mismatch in IDAT", std::runtime_error);
  Bytes header = good;
  header[16 + 3] ^= 0x01;  // IHDR width
  CHECK_THROWS_WITH_AS(decode(header), "CRC mismatch in IHDR", std::runtime_error);
}

TEST_CASE("PNG writer: set ignores pixels outside, at reads back, bad sizes throw") {
  io::RgbImage img(4, 2);
  img.set(-1, 0, {255, 0, 0});
  img.set(4, 1, {255, 0, 0});
  img.set(3, 1, {1, 2, 3});
  CHECK(img.at(3, 1) == io::RgbImage::Color{1, 2, 3});
  CHECK(img.at(0, 0) == io::RgbImage::Color{0, 0, 0});
  CHECK_THROWS_AS(io::RgbImage(0, 5), std::invalid_argument);
  CHECK_THROWS_AS(io::RgbImage(5, 70000), std::invalid_argument);
}

TEST_CASE("PNG writer: write_png writes encode_png's bytes; an unwritable path throws naming it") {
  const streamclust::test::TempDir dir("png_writer", "file");
  const std::string path = dir.path("image.png");
  const io::RgbImage img = pattern(33, 17);
  io::write_png(path, img);
  std::ifstream in(path, std::ios::binary);
  const Bytes bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(bytes == io::encode_png(img));
  const std::string bad = dir.path("no/such/dir/image.png");
  std::string message;
  try {
    io::write_png(bad, img);
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  CHECK(message.find(bad) != std::string::npos);
}
