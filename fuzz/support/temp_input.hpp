// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A per-process scratch file for fuzz inputs that only a path can reach
/// (the point readers open files): `<temp dir>/streamclust-fuzz-<pid>-<name>`,
/// rewritten for every input and removed when the process exits normally.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include <unistd.h>

namespace streamclust::fuzz {

class TempInput {
 public:
  /// `name` ends the file name; its extension is what format detection sees.
  explicit TempInput(const std::string& name) {
    std::error_code ec;
    std::filesystem::path dir = std::filesystem::temp_directory_path(ec);
    if (ec) dir = "/tmp";
    path_ = (dir / ("streamclust-fuzz-" + std::to_string(::getpid()) + "-" + name)).string();
  }
  ~TempInput() { std::remove(path_.c_str()); }
  TempInput(const TempInput&) = delete;
  TempInput& operator=(const TempInput&) = delete;

  /// Replaces the file's content with `data[0..size)`; returns its path.
  /// Aborts when the file cannot be written (the harness is broken, not the input).
  const std::string& write(const std::uint8_t* data, std::size_t size) {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    if (!f || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
      std::fprintf(stderr, "fuzz: cannot write the scratch file %s\n", path_.c_str());
      std::abort();
    }
    return path_;
  }
  const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
};

}  // namespace streamclust::fuzz
