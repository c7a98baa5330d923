// SPDX-License-Identifier: MIT
#pragma once
// A fresh directory under the system temp directory, removed at scope exit.

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <system_error>

namespace streamclust::test {

struct TempDir {
  std::filesystem::path dir;
  /// `prefix` names the test file, `name` the test case (keeps runs apart).
  TempDir(const std::string& prefix, const std::string& name) {
    std::random_device rd;
    dir = std::filesystem::temp_directory_path() / ("streamclust_" + prefix + "_" + name + "_" + std::to_string(rd()));
    std::filesystem::create_directories(dir);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  /// Writes `content` (binary) to a file in the directory; returns its path.
  std::string file(const std::string& name, const std::string& content) const {
    const std::string p = (dir / name).string();
    std::ofstream(p, std::ios::binary) << content;
    return p;
  }
  std::string path(const std::string& name) const { return (dir / name).string(); }
};

}  // namespace streamclust::test
