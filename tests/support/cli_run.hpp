// SPDX-License-Identifier: MIT
#pragma once
// Runs the streamclust CLI in-process and reads its output files (CLI tests).

#include "cli/main.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace streamclust::test {

/// Exit code and captured streams of one in-process CLI run.
struct RunResult {
  int code;
  std::string out, err;
};

/// `streamclust <args...>` through cli::run_main, stdout/stderr captured.
inline RunResult run_cli(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  const int code = cli::run_main(args, out, err);
  return {code, out.str(), err.str()};
}

/// The whole content of a file ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace streamclust::test
