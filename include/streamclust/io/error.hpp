// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The one exception type of the I/O module: a problem in an input file,
/// located precisely. `what()` reads "FILE: WHERE: WHAT", for example
///
///     scan.pcd: byte 4211: truncated binary data: expected 240887 points of 16 bytes, file ends after 263 points
///     a.csv: line 17, column 3 (z): expected a number, found "abc"
///
/// WHERE is one of "line N", "line N, column K (name)", "byte N" or "header".

#include <stdexcept>
#include <string>
#include <utility>

namespace streamclust::io {

/// An input file that cannot be read as what it claims to be. Thrown by
/// `open_reader` and `PointReader::read`; never a crash, a hang or a silent stop.
class InputError : public std::runtime_error {
 public:
  /// \param file  the path as given by the caller
  /// \param where "line N", "line N, column K (name)", "byte N" or "header"
  /// \param what  what was expected and what was found
  InputError(std::string file, std::string where, std::string what)
      : std::runtime_error(file + ": " + where + ": " + what),
        file_(std::move(file)),
        where_(std::move(where)),
        what_(std::move(what)) {}

  /// The path of the offending file.
  const std::string& file() const noexcept { return file_; }
  /// The place in the file: "line N", "line N, column K (name)", "byte N" or "header".
  const std::string& where() const noexcept { return where_; }
  /// What was expected (and what was found), without file and place.
  const std::string& what_expected() const noexcept { return what_; }

 private:
  std::string file_;
  std::string where_;
  std::string what_;
};

}  // namespace streamclust::io
