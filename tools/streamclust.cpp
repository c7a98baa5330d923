// SPDX-License-Identifier: MIT
// The `streamclust` command-line tool (docs/cli.md).

#include "cli/main.hpp"

#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  const std::vector<std::string> args(argv + 1, argv + argc);
  return streamclust::cli::run_main(args, std::cout, std::cerr);
}
