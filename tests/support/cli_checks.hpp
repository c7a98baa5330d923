// SPDX-License-Identifier: MIT
#pragma once
// Checks on the output files of in-process CLI runs (the live and ROS 2 tests).

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "temp_dir.hpp"

#include <string>
#include <vector>

namespace streamclust::test {

/// The JSON document in the file `path`.
inline nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(slurp(path)); }

/// `cluster RECORDED` with the run's options (`preset`) gives the same label
/// rows as the run wrote to `run_labels`.
inline void check_offline_equal(const TempDir& dir, const std::string& run_labels, const std::string& recorded,
                                const std::vector<std::string>& preset) {
  std::vector<std::string> args{"cluster", recorded, "--labels", dir.path("offline.csv"), "--cycles", "all", "-q"};
  args.insert(args.end(), preset.begin(), preset.end());
  const RunResult offline = run_cli(args);
  REQUIRE_MESSAGE(offline.code == 0, offline.err);
  const std::string a = slurp(run_labels), b = slurp(dir.path("offline.csv"));
  CHECK(a.size() > 1000);  // many cycles of many points
  CHECK(a == b);
}

}  // namespace streamclust::test
