// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The control side of `streamclust live`: the library's LiDAR connections
/// (<streamclust/live/sdk2_session.hpp>, <streamclust/live/sdk1_session.hpp>)
/// set from the live options. Their ConnectionError is the tool's
/// NetworkError (exit code 6).

#include "cli/live.hpp"

#include <streamclust/live/lidar_connection.hpp>
#include <streamclust/live/sdk1_session.hpp>
#include <streamclust/live/sdk2_session.hpp>

#include <chrono>
#include <ostream>
#include <string>
#include <vector>

namespace streamclust::cli {

using live::bind_or_fail;
using live::FoundLidar;

/// SDK2 discovery of the LiDAR chosen by --lidar (any when none is given).
inline FoundLidar discover_sdk2(const LiveOptions& o, std::chrono::steady_clock::duration timeout, std::ostream& err) {
  live::Sdk2DiscoveryOptions d;
  d.host_address = o.source.host_address;
  d.request_address = o.discovery_address.value_or(0xFFFFFFFFu);
  d.lidars = o.lidars;
  d.timeout = timeout;
  d.notes = o.cluster.quiet ? nullptr : &err;
  return live::discover_sdk2(d);
}

/// --configure: points the LiDAR's streams at this host; returns the host address.
inline std::uint32_t configure_sdk2(const LiveOptions& o, const FoundLidar& lidar, std::ostream& err) {
  live::Sdk2ConfigureOptions c;
  c.host_address = o.source.host_address;
  c.point_port = o.source.port;
  c.data_type = o.data_type;
  c.work_mode_sampling = o.work_mode_sampling;
  c.notes = o.cluster.quiet ? nullptr : &err;
  return live::configure_sdk2(lidar, c);
}

/// The SDK1 connection of a live run to the LiDAR chosen by `lidars` (any
/// when empty); the run's `index`-th LiDAR commands from port PORT + 500 +
/// index (the data port, PORT + 1000, is shared).
class Sdk1Session : public live::Sdk1Session {
 public:
  Sdk1Session(const LiveOptions& o, const std::vector<std::string>& lidars, std::size_t index,
              std::chrono::steady_clock::duration timeout, std::ostream& err)
      : live::Sdk1Session(options(o, lidars, index, timeout, err)) {}

 private:
  static live::Sdk1SessionOptions options(const LiveOptions& o, const std::vector<std::string>& lidars,
                                          std::size_t index, std::chrono::steady_clock::duration timeout,
                                          std::ostream& err) {
    live::Sdk1SessionOptions s;
    s.host_address = o.source.host_address;
    s.listen_port = o.source.port;
    s.command_port = static_cast<std::uint16_t>(o.source.port + 500 + index);
    s.lidars = lidars;
    s.timeout = timeout;
    s.notes = o.cluster.quiet ? nullptr : &err;
    return s;
  }
};

}  // namespace streamclust::cli
