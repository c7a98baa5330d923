// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Internals of the PCD and PLY readers: what may follow the data a header
/// declares. Text (ascii) files may end with blank lines (spaces, tabs, CR;
/// a final newline or none); binary files must end with the last declared
/// byte. Anything else is an InputError naming the line or the byte offset.

#include <streamclust/io/error.hpp>
#include <streamclust/io/input_stream.hpp>

#include <cstdint>
#include <limits>
#include <string>

namespace streamclust::io::detail {

/// Reads the rest of a text file: only blank lines may be left. `declared`
/// completes "expected end of file after ...", e.g. "the 3 points POINTS
/// declares". `line_no` counts the lines read so far. O(bytes left).
inline void expect_text_end(ByteSource& src, std::string& line, std::uint64_t& line_no, const std::string& declared) {
  for (;;) {
    const auto st = src.read_line(line, max_line_bytes);
    if (st == ByteSource::LineStatus::eof) return;
    ++line_no;
    if (st == ByteSource::LineStatus::too_long)
      throw InputError(src.path(), where_line(line_no),
                       "expected end of file after " + declared + ", found a line longer than " +
                           std::to_string(max_line_bytes) + " bytes");
    if (!trim(line).empty())
      throw InputError(src.path(), where_line(line_no),
                       "expected end of file after " + declared + ", found " + quoted(trim(line)));
  }
}

/// Throws "byte AT: N bytes after DECLARED: expected end of file" (N
/// omitted when the file size is unknown, UINT64_MAX).
[[noreturn]] inline void throw_trailing_bytes(const std::string& path, std::uint64_t at, std::uint64_t file_size,
                                              const std::string& declared) {
  const bool known = file_size != std::numeric_limits<std::uint64_t>::max();
  const std::uint64_t n = known ? file_size - at : 0;
  const std::string what = !known ? std::string("bytes") : std::to_string(n) + (n == 1 ? " byte" : " bytes");
  throw InputError(path, where_byte(at), what + " after " + declared + ": expected end of file");
}

/// Requires a binary file to end here. `declared` completes "... bytes after
/// ...", e.g. "the declared data (POINTS 10 x 16 bytes)". O(1).
inline void expect_binary_end(ByteSource& src, const std::string& declared) {
  const std::uint64_t at = src.offset();
  if (!src.at_end()) throw_trailing_bytes(src.path(), at, src.size(), declared);
}

}  // namespace streamclust::io::detail
