// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust live SOURCE`: clusters a Livox LiDAR's stream as it arrives
/// over the network (SDK2: Mid-360, HAP; SDK1: Avia, Mid-40/70, Horizon,
/// Tele-15), with the outputs of `cluster`, a raw recording, a Foxglove
/// live view and a status line. The options of `cluster` (presets,
/// policies, outputs) apply unchanged; SOURCE and the options below are
/// the live command's own (docs/live.md).

#include "cli/options.hpp"

#include <streamclust/live/lidar_connection.hpp>
#include <streamclust/live/livox_source.hpp>

#include <chrono>
#include <cstdint>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::cli {

/// Exit code 6: the network failed the run (a port that cannot be bound, no
/// LiDAR answering discovery or a handshake, a socket error).
inline constexpr int kNetworkError = 6;

/// A network failure (exit code 6), naming the endpoint and the OS reason:
/// the library's LiDAR-connection error.
using NetworkError = live::ConnectionError;

using live::kSdk1BroadcastPort;
using live::kSdk2PointPort;
using live::LivoxProtocol;
using live::LivoxSourceUrl;

/// Parses a source URL; UsageError naming what was expected.
LivoxSourceUrl parse_livox_url(const std::string& text);

/// Parses `--foxglove [ADDRESS:]PORT` (address default 0.0.0.0, every
/// interface; port 0: any free one); UsageError naming what was expected.
std::pair<std::string, std::uint16_t> parse_foxglove_endpoint(const std::string& text);

struct LiveOptions {
  LivoxSourceUrl source;
  std::string source_text;            ///< as given, for messages and the report
  bool configure = false;             ///< SDK2: discovery, then point the LiDAR's destinations at this host
  std::vector<std::string> lidars;    ///< --lidar: serial numbers or addresses (empty: the first one heard)
  std::optional<std::uint32_t> discovery_address;  ///< where discovery requests go (default 255.255.255.255)
  std::optional<std::uint8_t> data_type;           ///< SDK2 --configure: point data type 1, 2 or 3
  bool work_mode_sampling = false;    ///< SDK2 --configure: also set the work mode to sampling
  double duration = 0.0;              ///< [s] of wall time; 0: until stopped
  double idle_exit = 0.0;             ///< [s] without packets ends the run; 0: never
  double first_packet_timeout = 10.0; ///< [s] to wait for discovery, a handshake and the first packet
  std::string record_path;            ///< --record FILE.mcap
  std::string foxglove;               ///< --foxglove [ADDR:]PORT; empty: no live view
  std::size_t queue_packets = 4096;   ///< receiver-to-engine queue per LiDAR [packets]
  std::size_t reorder_packets = 8;    ///< packets held to undo reordering
  std::size_t socket_buffer_bytes = 8u << 20;
  bool status = true;                 ///< the status line on stderr (off with --quiet or --no-status)
  ClusterOptions cluster;             ///< preset, policies and the outputs of `cluster`
};

/// Parses `streamclust live` arguments.
LiveOptions parse_live_options(const std::vector<std::string>& args);

/// The help of `streamclust live`.
std::string live_help();

/// Runs `streamclust live`. Returns the exit code; throws UsageError (2),
/// NetworkError (6).
int run_live(const LiveOptions& o, std::ostream& out, std::ostream& err);

}  // namespace streamclust::cli
