// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A binary file read at explicit offsets (containers with indexes and
/// footers: MCAP, ROS 1 bags, LVX), with reads checked against the file size.

#include <streamclust/io/error.hpp>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace streamclust::io::detail {

/// A regular file opened for reading at offsets. Every read is checked against
/// the size found at opening, so a length read from the file can never make
/// the reader allocate or read beyond the file. Not thread-safe.
class BinaryFile {
 public:
  /// Opens `path`; throws InputError "cannot open" when it cannot, or when it
  /// is not a regular file of known size.
  explicit BinaryFile(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw InputError(path, "byte 0", "cannot open");
    in_.seekg(0, std::ios::end);
    const std::streamoff end = in_.tellg();
    if (!in_ || end < 0) throw InputError(path, "byte 0", "cannot open: not a regular file (size unknown)");
    size_ = static_cast<std::uint64_t>(end);
    in_.seekg(0);
  }

  const std::string& path() const noexcept { return path_; }
  std::uint64_t size() const noexcept { return size_; }

  /// True when `n` bytes starting at `offset` lie inside the file.
  bool contains(std::uint64_t offset, std::uint64_t n) const noexcept {
    return offset <= size_ && n <= size_ - offset;
  }

  /// Reads `n` bytes at `offset` into `out` (resized to n). Throws InputError
  /// "truncated WHAT" naming the offset when the file ends first. O(n).
  void read_at(std::uint64_t offset, std::uint64_t n, std::vector<std::uint8_t>& out, const char* what) {
    if (!contains(offset, n)) {
      throw InputError(path_, "byte " + std::to_string(offset),
                       std::string("truncated ") + what + ": expected " + std::to_string(n) +
                           " bytes, the file ends after " + std::to_string(offset <= size_ ? size_ - offset : 0));
    }
    out.resize(static_cast<std::size_t>(n));
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(offset));
    if (n > 0) in_.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(n));
    if (!in_) throw InputError(path_, "byte " + std::to_string(offset), std::string("cannot read ") + what);
  }

 private:
  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

}  // namespace streamclust::io::detail
