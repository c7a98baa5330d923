// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The `streamclust` command: subcommand dispatch, help texts and the
/// mapping of errors to exit codes (0 ok, 2 usage, 3 verification mismatch,
/// 4 input error, 5 out of memory, 6 network error). Callable from tests
/// without spawning a process; defined in cli/main.cpp, so a caller compiles
/// none of the commands.

#include <ostream>
#include <string>
#include <vector>

namespace streamclust::cli {

/// Runs the command line `args` (without the program name); returns the
/// process exit code. Messages go to `err`, results to `out`.
int run_main(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

/// The message on `err` and the exit code of the exception being handled
/// by `command` (call it only inside a catch block).
int report_exception(const std::string& command, std::ostream& err);

/// Help texts (`streamclust --help`, `cluster --help`, ...).
const char* main_help();
std::string cluster_help();
const char* info_help();
const char* simulate_help();
std::string evaluate_help();

}  // namespace streamclust::cli
