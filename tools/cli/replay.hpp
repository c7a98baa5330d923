// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust replay INPUT --to livox-sdk2://HOST[:PORT]` (or
/// livox-sdk1://): a Livox LiDAR emulated on the network
/// (cli/livox_emulator.hpp), sending any readable input, or a simulated
/// scene, as the device's packets at the device's rate, with faults on
/// demand. For tests of `live` and for users without hardware.

#include "cli/livox_emulator.hpp"
#include "cli/options.hpp"
#include "cli/simulate.hpp"

#include <ostream>
#include <string>
#include <vector>

namespace streamclust::cli {

struct ReplayOptions {
  std::string input;             ///< a point file or recording; empty with --simulate
  io::ReadOptions read;
  bool simulate = false;         ///< a simulated scene instead of INPUT (the options of simulate)
  SimulateOptions simulation;
  EmulatorOptions emulator;
  bool quiet = false;
};

ReplayOptions parse_replay_options(const std::vector<std::string>& args);
std::string replay_help();
/// Runs `streamclust replay`; returns the exit code. Throws UsageError (2),
/// io::InputError (4), NetworkError (6).
int run_replay(const ReplayOptions& o, std::ostream& out, std::ostream& err);

}  // namespace streamclust::cli
