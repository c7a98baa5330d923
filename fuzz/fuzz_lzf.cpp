// SPDX-License-Identifier: MIT
// Fuzz target: the LZF codec (io/lzf.hpp). The first 2 bytes of an input
// declare an uncompressed size (0 to 64 KiB); the rest is decompressed
// into exactly that many bytes (never out of bounds, an error string or
// exactly the declared size). Then the whole input is compressed and
// decompressed back: the same bytes, within the documented size bound, and
// a wrong declared size is refused. O(input + 64 KiB) per input.

#include "support/expect.hpp"

#include <streamclust/io/lzf.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace {

namespace io = streamclust::io;
using streamclust::fuzz::require;

/// Decompression of arbitrary bytes into an arbitrary declared size. The
/// output buffer is exactly that size, so ASan catches any write past it.
void decompress_arbitrary(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return;
  const std::size_t declared = std::size_t{data[0]} | std::size_t{data[1]} << 8;
  std::vector<unsigned char> in(data + 2, data + size);  // its own allocation: reads past it are caught
  std::vector<unsigned char> out(declared);
  const std::string error = io::lzf_decompress(in.data(), in.size(), out.data(), out.size());
  if (in.empty()) require(error.empty() == (declared == 0), "empty data decompresses to 0 bytes only");
}

/// Round trip of the input through lzf_compress and lzf_decompress.
void round_trip(const std::uint8_t* data, std::size_t size) {
  const std::vector<unsigned char> compressed = io::lzf_compress(data, size);
  require(compressed.size() <= size + size / 32 + 1, "compressed size within n + n / 32 + 1");
  std::vector<unsigned char> back(size);
  require(io::lzf_decompress(compressed.data(), compressed.size(), back.data(), back.size()).empty(),
          "the compressor's output decompresses");
  require(size == 0 || std::memcmp(back.data(), data, size) == 0, "the round trip gives the input back");
  std::vector<unsigned char> longer(size + 1);
  require(!io::lzf_decompress(compressed.data(), compressed.size(), longer.data(), longer.size()).empty(),
          "a declared size one byte too long is refused");
  if (size > 0) {
    std::vector<unsigned char> shorter(size - 1);
    require(!io::lzf_decompress(compressed.data(), compressed.size(), shorter.data(), shorter.size()).empty(),
            "a declared size one byte too short is refused");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  decompress_arbitrary(data, size);
  round_trip(data, size);
  return 0;
}
