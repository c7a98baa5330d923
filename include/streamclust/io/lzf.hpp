// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// LZF (liblzf format, as used by PCD binary_compressed): a bounds-checked
/// decompressor and a simple greedy hash-based compressor.
///
/// Stream format: a control byte `c`
///  - c < 32: a literal run, copy the next c + 1 bytes;
///  - else a back reference: length L = (c >> 5) (if 7, add the next byte),
///    offset = ((c & 0x1f) << 8 | next byte) + 1 bytes back; copy L + 2 bytes
///    (the copy may overlap its own output).

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace streamclust::io {

/// Decompresses `in[0..in_size)` into exactly `out_size` bytes at `out`.
/// Returns "" on success, else a description of the first inconsistency
/// (with its byte offset in the compressed data). Never reads or writes out of bounds.
inline std::string lzf_decompress(const unsigned char* in, std::size_t in_size, unsigned char* out,
                                  std::size_t out_size) {
  std::size_t ip = 0;
  std::size_t op = 0;
  while (ip < in_size) {
    const std::size_t at = ip;
    const unsigned ctrl = in[ip++];
    if (ctrl < 32) {
      const std::size_t len = ctrl + 1u;
      if (len > in_size - ip)
        return "LZF literal run at compressed byte " + std::to_string(at) + " runs past the end of the data";
      if (len > out_size - op)
        return "LZF literal run at compressed byte " + std::to_string(at) + " overflows the declared uncompressed size";
      std::memcpy(out + op, in + ip, len);
      ip += len;
      op += len;
    } else {
      std::size_t len = ctrl >> 5;
      if (len == 7) {
        if (ip >= in_size) return "LZF back reference at compressed byte " + std::to_string(at) + " is truncated";
        len += in[ip++];
      }
      if (ip >= in_size) return "LZF back reference at compressed byte " + std::to_string(at) + " is truncated";
      const std::size_t dist = (((ctrl & 0x1fu) << 8) | in[ip++]) + 1u;
      len += 2;
      if (dist > op)
        return "LZF back reference at compressed byte " + std::to_string(at) + " points before the start of the output";
      if (len > out_size - op)
        return "LZF back reference at compressed byte " + std::to_string(at) +
               " overflows the declared uncompressed size";
      for (std::size_t k = 0; k < len; ++k, ++op) out[op] = out[op - dist];
    }
  }
  if (op != out_size) {
    return "LZF data decompresses to " + std::to_string(op) + " bytes, the header declares " +
           std::to_string(out_size);
  }
  return {};
}

/// Compresses `in[0..n)` to LZF (greedy, 3-byte hash, 8 KiB window). Always
/// succeeds; the output is at most n + n / 32 + 1 bytes.
inline std::vector<unsigned char> lzf_compress(const unsigned char* in, std::size_t n) {
  std::vector<unsigned char> out;
  out.reserve(n + n / 32 + 16);
  constexpr std::size_t hash_bits = 14;
  constexpr std::size_t max_off = 8192;  // distances 1..8192
  constexpr std::size_t max_len = 264;   // 7 + 255 + 2
  std::vector<std::size_t> table(std::size_t{1} << hash_bits, static_cast<std::size_t>(-1));
  std::size_t lit_start = 0;  // first byte of the pending literal run
  auto flush_literals = [&](std::size_t end) {
    while (lit_start < end) {
      const std::size_t len = end - lit_start < 32 ? end - lit_start : 32;
      out.push_back(static_cast<unsigned char>(len - 1));
      out.insert(out.end(), in + lit_start, in + lit_start + len);
      lit_start += len;
    }
  };
  auto hash = [&](std::size_t i) -> std::size_t {
    const std::uint32_t v = (std::uint32_t{in[i]} << 16) | (std::uint32_t{in[i + 1]} << 8) | in[i + 2];
    return static_cast<std::size_t>((v * 2654435761u) >> (32 - hash_bits));
  };
  std::size_t i = 0;
  while (i + 2 < n) {
    const std::size_t h = hash(i);
    const std::size_t cand = table[h];
    table[h] = i;
    if (cand != static_cast<std::size_t>(-1) && i - cand <= max_off && in[cand] == in[i] &&
        in[cand + 1] == in[i + 1] && in[cand + 2] == in[i + 2]) {
      std::size_t len = 3;
      while (len < max_len && i + len < n && in[cand + len] == in[i + len]) ++len;
      flush_literals(i);
      const std::size_t off = i - cand - 1;
      const std::size_t l = len - 2;
      if (l < 7) {
        out.push_back(static_cast<unsigned char>((l << 5) | (off >> 8)));
      } else {
        out.push_back(static_cast<unsigned char>((7u << 5) | (off >> 8)));
        out.push_back(static_cast<unsigned char>(l - 7));
      }
      out.push_back(static_cast<unsigned char>(off & 0xffu));
      for (std::size_t k = i + 1; k < i + len && k + 2 < n; ++k) table[hash(k)] = k;
      i += len;
      lit_start = i;
    } else {
      ++i;
    }
  }
  flush_literals(n);
  return out;
}

}  // namespace streamclust::io
