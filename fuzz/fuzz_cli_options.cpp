// SPDX-License-Identifier: MIT
// Fuzz target: the command-line parsers of the `streamclust` tool
// (tools/cli). An input is an argument list, one argument per line; it goes
// to every parser of user input: cluster, info, simulate, evaluate and
// evaluate --objects options, and --mount's value. UsageError is the
// documented outcome of a bad argument list; any other exception type, a
// crash or undefined behaviour is a bug, and so is a list that parses into
// values the tool documents as impossible (an even mask, a window of no
// points, a non-finite rate, ...). O(input) per input.

#include "support/expect.hpp"

#include "cli/evaluate.hpp"
#include "cli/evaluate_objects.hpp"
#include "cli/options.hpp"
#include "cli/simulate.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace {

namespace cli = streamclust::cli;
using streamclust::fuzz::only_throws;
using streamclust::fuzz::require;

/// At most this many arguments per input: parsing is linear, this keeps
/// inputs fast whatever libFuzzer's -max_len.
constexpr std::size_t kMaxArguments = 64;

std::vector<std::string> split_lines(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args;
  std::string current;
  for (std::size_t i = 0; i < size && args.size() < kMaxArguments; ++i) {
    if (data[i] == '\n') {
      args.push_back(current);
      current.clear();
    } else {
      current += static_cast<char>(data[i]);
    }
  }
  if (!current.empty() && args.size() < kMaxArguments) args.push_back(current);
  return args;
}

bool finite_positive(double v) { return std::isfinite(v) && v > 0.0; }

/// What cluster's and evaluate's policy options promise once parsed.
void check_policy(const cli::ClusterOptions& o) {
  require(o.mask >= 1 && o.mask <= 255 && o.mask % 2 == 1, "--mask: an odd number of cells from 1 to 255");
  const auto cap = o.params.get<streamclust::CappedGrid>().capacity;
  require(cap >= 1 && cap <= 255, "--cap: 1 to 255 points per cell");
  require(o.window_count >= 1, "--window-count: at least one point");
  require(std::isfinite(o.window_seconds) && o.window_seconds >= 0.0, "--window-time: finite seconds >= 0");
  require(finite_positive(o.rate_hz), "--rate: finite and > 0");
  require(finite_positive(o.max_time_jump), "--max-time-jump: finite and > 0");
  require(finite_positive(o.params.get<streamclust::AngularLinkage>().theta_deg), "--theta: finite and > 0");
  require(finite_positive(o.params.get<streamclust::EuclideanLinkage>().max_distance) &&
              finite_positive(o.params.get<streamclust::RangeAdaptiveLinkage>().min_distance),
          "--distance, --min-distance: finite and > 0");
  require(finite_positive(o.max_multiplicity), "--max-multiplicity: finite and > 0");
  if (o.grid) require(o.grid->first >= 1 && o.grid->second >= 1, "--grid: at least one row and one column");
  if (o.read.point_rate) require(finite_positive(*o.read.point_rate), "--point-rate: finite and > 0");
}

void check_cluster(const cli::ClusterOptions& o) {
  check_policy(o);
  require(!o.input.empty(), "cluster: an input file");
  require(!(o.verify && o.mode == cli::Mode::frame), "--verify: continuous mode only");
  if (o.read.topic) require(!o.read.topic->empty(), "--topic: a non-empty name");
  if (o.mount_deg) {
    for (const double a : *o.mount_deg) require(std::isfinite(a) && std::abs(a) <= 360.0, "--mount: angles within +-360");
  }
  if (o.sensor_height) require(*o.sensor_height > 0.0f && *o.sensor_height <= 100.0f, "--sensor-height: (0, 100] m");
  require(o.ground_tolerance >= 0.0f && o.ground_tolerance <= 2.0f, "--ground-tolerance: [0, 2] m");
  require(o.ground_cell > 0.05f && o.ground_cell <= 10.0f, "--ground-cell: (0.05, 10] m");
  require(o.max_slope_deg >= 0.0f && o.max_slope_deg <= 60.0f, "--max-slope: [0, 60] degrees");
}

void check_simulation(const cli::SimulateOptions& o) {
  require(finite_positive(o.seconds), "--seconds: finite and > 0");
  require(finite_positive(o.point_rate), "--point-rate: finite and > 0");
  require(finite_positive(o.max_range), "--max-range: finite and > 0");
  require(o.seed >= 1, "--seed: a whole number >= 1");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::string> args = split_lines(data, size);
  cli::ClusterOptions cluster;
  if (only_throws<cli::UsageError>([&] { cluster = cli::parse_cluster_options(args); })) check_cluster(cluster);
  cli::InfoOptions info;
  if (only_throws<cli::UsageError>([&] { info = cli::parse_info_options(args); })) {
    require(!info.input.empty(), "info: an input file");
    if (info.read.point_rate) require(finite_positive(*info.read.point_rate), "--point-rate: finite and > 0");
  }
  cli::SimulateOptions simulate;
  if (only_throws<cli::UsageError>([&] { simulate = cli::parse_simulate_options(args); })) check_simulation(simulate);
  cli::EvaluateOptions evaluate;
  if (only_throws<cli::UsageError>([&] { evaluate = cli::parse_evaluate_options(args); })) {
    check_policy(evaluate.policy);
    check_simulation(evaluate.scenario);
    require(evaluate.policy.window_seconds > 0.0, "evaluate: a window T_B > 0");
  }
  cli::EvaluateObjectsOptions objects;
  if (only_throws<cli::UsageError>([&] { objects = cli::parse_evaluate_objects_options(args); })) {
    check_simulation(objects.scenario);
    require(finite_positive(objects.window_seconds) && objects.window_seconds <= 60.0, "--window-time: (0, 60] s");
    require(finite_positive(objects.rate_hz) && objects.rate_hz <= 10000.0, "--rate: (0, 10000] Hz");
    require(objects.height >= 0.0f && objects.height <= 100.0f, "--height: (0, 100] m, or 0 for the default");
    for (const auto* list : {&objects.euclidean_distances, &objects.frame_distances, &objects.plane_distances}) {
      require(!list->empty(), "--distance, --*-distances, --plane-distance: one value or more");
      for (const float v : *list) {
        require(finite_positive(v), "--distance, --*-distances, --plane-distance: finite and > 0");
      }
    }
    require(cli::ToolRegistry::choose(streamclust::registry::Slot::linkage, objects.linkage) == objects.linkage,
            "--linkage: a registered linkage");
  }
  for (const std::string& a : args) {
    std::array<double, 3> mount{};
    if (only_throws<cli::UsageError>([&] { mount = cli::parse_mount(a); })) {
      for (const double v : mount) require(std::isfinite(v) && std::abs(v) <= 360.0, "--mount: angles within +-360");
    }
  }
  return 0;
}
