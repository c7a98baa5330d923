// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Decompressing the chunks of recordings: LZ4 frames (MCAP "lz4", ROS 1
/// bags "lz4"), Zstandard frames (MCAP "zstd") and bzip2 streams (ROS 1 bags
/// "bz2"), through Debian's liblz4, libzstd and libbz2 (link
/// streamclust::recordings).
///
/// A chunk states its decompressed size; the output grows only as data really
/// decompresses and never beyond that size, so a size that lies costs no
/// memory, and a stream that ends early, runs long or is corrupt is an
/// InputError naming the chunk.

#include <streamclust/io/error.hpp>

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace streamclust::io {

/// Chunk compressions of recordings.
enum class Compression { none, lz4, zstd, bz2 };

/// The largest decompressed chunk a reader accepts [bytes] (writers use
/// chunks of 768 KiB to a few MiB; a bag's default is 768 KiB).
inline constexpr std::uint64_t max_chunk_bytes = std::uint64_t{1} << 30;

namespace detail {

/// Throws InputError(file, where, "corrupt COMPRESSION data: ...").
[[noreturn]] inline void fail_decompress(const std::string& file, const std::string& where, const char* codec,
                                         const std::string& detail) {
  throw InputError(file, where, std::string("corrupt ") + codec + " data: " + detail);
}

/// Grows `out` for the next output step: doubling from 64 KiB, at most to `expected`.
inline void grow_output(std::vector<std::uint8_t>& out, std::size_t used, std::uint64_t expected) {
  if (used < out.size()) return;
  const std::uint64_t next = std::min<std::uint64_t>(expected, std::max<std::uint64_t>(65536, 2 * std::uint64_t{out.size()}));
  out.resize(static_cast<std::size_t>(next));
}

inline std::size_t lz4_frame(const std::uint8_t* src, std::size_t n, std::vector<std::uint8_t>& out,
                             std::uint64_t expected, const std::string& file, const std::string& where) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) throw std::bad_alloc();
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(raw, LZ4F_freeDecompressionContext);
  std::size_t in = 0, used = 0;
  std::size_t hint = 1;
  while (hint != 0) {
    if (in == n) fail_decompress(file, where, "lz4", "the frame ends early (after " + std::to_string(used) + " bytes)");
    grow_output(out, used, expected);
    if (used == out.size()) {
      // Full: the frame may only have its end mark left.
      std::uint8_t probe = 0;
      std::size_t probe_size = 1, src_size = n - in;
      hint = LZ4F_decompress(ctx.get(), &probe, &probe_size, src + in, &src_size, nullptr);
      if (LZ4F_isError(hint)) fail_decompress(file, where, "lz4", LZ4F_getErrorName(hint));
      if (probe_size != 0) fail_decompress(file, where, "lz4", "more than the declared " + std::to_string(expected) + " bytes");
      in += src_size;
      continue;
    }
    std::size_t dst_size = out.size() - used, src_size = n - in;
    hint = LZ4F_decompress(ctx.get(), out.data() + used, &dst_size, src + in, &src_size, nullptr);
    if (LZ4F_isError(hint)) fail_decompress(file, where, "lz4", LZ4F_getErrorName(hint));
    used += dst_size;
    in += src_size;
    if (dst_size == 0 && src_size == 0) fail_decompress(file, where, "lz4", "no progress");
  }
  if (in != n) fail_decompress(file, where, "lz4", std::to_string(n - in) + " bytes after the end of the frame");
  return used;
}

inline std::size_t zstd_frame(const std::uint8_t* src, std::size_t n, std::vector<std::uint8_t>& out,
                              std::uint64_t expected, const std::string& file, const std::string& where) {
  const std::unique_ptr<ZSTD_DStream, decltype(&ZSTD_freeDStream)> ctx(ZSTD_createDStream(), ZSTD_freeDStream);
  if (!ctx) throw std::bad_alloc();
  ZSTD_inBuffer input{src, n, 0};
  std::size_t used = 0, hint = 1;
  while (hint != 0) {
    grow_output(out, used, expected);
    std::uint8_t probe = 0;
    const bool full = used == out.size();
    ZSTD_outBuffer output{full ? &probe : out.data() + used, full ? 1 : out.size() - used, 0};
    const std::size_t before = input.pos;
    hint = ZSTD_decompressStream(ctx.get(), &output, &input);
    if (ZSTD_isError(hint)) fail_decompress(file, where, "zstd", ZSTD_getErrorName(hint));
    if (full && output.pos != 0) fail_decompress(file, where, "zstd", "more than the declared " + std::to_string(expected) + " bytes");
    used += full ? 0 : output.pos;
    if (hint != 0 && input.pos == n && output.pos == 0 && before == input.pos)
      fail_decompress(file, where, "zstd", "the frame ends early (after " + std::to_string(used) + " bytes)");
  }
  if (input.pos != n) fail_decompress(file, where, "zstd", std::to_string(n - input.pos) + " bytes after the end of the frame");
  return used;
}

inline std::size_t bz2_stream(const std::uint8_t* src, std::size_t n, std::vector<std::uint8_t>& out,
                              std::uint64_t expected, const std::string& file, const std::string& where) {
  if (n > std::numeric_limits<unsigned>::max()) fail_decompress(file, where, "bz2", "chunk above 4 GiB");
  bz_stream s{};
  if (BZ2_bzDecompressInit(&s, 0, 0) != BZ_OK) throw std::bad_alloc();
  const std::unique_ptr<bz_stream, int (*)(bz_stream*)> guard(&s, BZ2_bzDecompressEnd);
  s.next_in = const_cast<char*>(reinterpret_cast<const char*>(src));  // bzlib's API is not const-correct
  s.avail_in = static_cast<unsigned>(n);
  std::size_t used = 0;
  for (;;) {
    grow_output(out, used, expected);
    char probe = 0;
    const bool full = used == out.size();
    const std::size_t room = full ? 1 : std::min<std::size_t>(out.size() - used, std::numeric_limits<unsigned>::max());
    s.next_out = full ? &probe : reinterpret_cast<char*>(out.data() + used);
    s.avail_out = static_cast<unsigned>(room);
    const int rc = BZ2_bzDecompress(&s);
    const std::size_t produced = room - s.avail_out;
    if (full && produced != 0) fail_decompress(file, where, "bz2", "more than the declared " + std::to_string(expected) + " bytes");
    if (!full) used += produced;
    if (rc == BZ_STREAM_END) break;
    if (rc != BZ_OK) fail_decompress(file, where, "bz2", "bzlib error " + std::to_string(rc));
    if (s.avail_in == 0 && produced == 0)
      fail_decompress(file, where, "bz2", "the stream ends early (after " + std::to_string(used) + " bytes)");
  }
  if (s.avail_in != 0) fail_decompress(file, where, "bz2", std::to_string(s.avail_in) + " bytes after the end of the stream");
  return used;
}

}  // namespace detail

/// Decompresses the `n` bytes at `src` into `out` (resized to exactly
/// `expected` bytes). Throws InputError(file, where, ...) when the data is
/// corrupt, decompresses to a different size than `expected`, or `expected`
/// exceeds max_chunk_bytes. O(expected); memory O(bytes actually produced).
inline void decompress(Compression c, const std::uint8_t* src, std::size_t n, std::uint64_t expected,
                       std::vector<std::uint8_t>& out, const std::string& file, const std::string& where) {
  if (expected > max_chunk_bytes) {
    throw InputError(file, where, "chunk of " + std::to_string(expected) + " bytes decompressed: expected at most " +
                                      std::to_string(max_chunk_bytes));
  }
  out.clear();
  std::size_t used = 0;
  switch (c) {
    case Compression::none:
      if (n != expected) {
        throw InputError(file, where, "uncompressed chunk of " + std::to_string(n) + " bytes, its header says " +
                                          std::to_string(expected));
      }
      out.assign(src, src + n);
      return;
    case Compression::lz4: used = detail::lz4_frame(src, n, out, expected, file, where); break;
    case Compression::zstd: used = detail::zstd_frame(src, n, out, expected, file, where); break;
    case Compression::bz2: used = detail::bz2_stream(src, n, out, expected, file, where); break;
  }
  if (used != expected) {
    throw InputError(file, where, "chunk decompresses to " + std::to_string(used) + " bytes, its header says " +
                                      std::to_string(expected));
  }
  out.resize(used);
}

}  // namespace streamclust::io
