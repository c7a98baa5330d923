// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The host's side of an SDK2 LiDAR (Mid-360, HAP) before it streams:
/// - discovery (0x0000 requests broadcast to port 56000, once a second,
///   until a chosen LiDAR answers),
/// - configure (one parameter write, 0x0100, pointing the point, IMU and
///   status streams at this host, optionally setting the data type and the
///   work mode; the ACK is checked).
/// Passive use sends nothing: the LiDAR streams to its stored destination.
/// Every wait is bounded; every failure is a ConnectionError naming the
/// endpoint and what did not answer. Facts and sources: docs/live.md.
///
/// Thread safety: each call owns its sockets; calls may run on any thread.

#include <streamclust/live/lidar_connection.hpp>
#include <streamclust/live/livox_stream.hpp>
#include <streamclust/live/sdk2_control.hpp>
#include <streamclust/live/sdk2_device.hpp>
#include <streamclust/live/sdk2_packets.hpp>
#include <streamclust/live/udp_socket.hpp>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <system_error>
#include <vector>

namespace streamclust::live {

/// SDK2 point packets as LivoxStream reads them.
inline LivoxPacketFormat sdk2_packet_format() {
  LivoxPacketFormat f;
  f.decode = [](const std::uint8_t* d, std::size_t n, LivoxPacketContents& out) { return decode_sdk2_packet(d, n, out); };
  return f;
}

struct Sdk2DiscoveryOptions {
  std::uint32_t host_address = 0;              ///< the interface to send from (0: every interface)
  std::uint32_t request_address = 0xFFFFFFFFu;  ///< where the requests go (a LiDAR's address without a broadcast route)
  std::vector<std::string> lidars;             ///< serial numbers or addresses to choose (empty: the first to answer)
  std::chrono::steady_clock::duration timeout = std::chrono::seconds(10);
  std::ostream* notes = nullptr;               ///< devices heard but not chosen (null: none)
};

/// SDK2 discovery: the first chosen LiDAR to answer; ConnectionError when
/// none does within `o.timeout` (it lists those that answered).
inline FoundLidar discover_sdk2(const Sdk2DiscoveryOptions& o) {
  const Endpoint local{o.host_address, sdk2_mid360_ports.discovery};
  auto socket = bind_or_fail(local, "SDK2 discovery: cannot listen on UDP " + format_endpoint(local));
  socket->enable_broadcast();
  const Endpoint to{o.request_address, sdk2_mid360_ports.discovery};
  std::vector<std::uint8_t> request;
  const auto until = std::chrono::steady_clock::now() + o.timeout;
  std::uint32_t seq = 1;
  std::vector<std::string> others;
  while (std::chrono::steady_clock::now() < until) {
    encode_sdk2_discovery_request(seq, request);
    if (!socket->send_to(to, request.data(), request.size())) {
      throw ConnectionError("SDK2 discovery: cannot send to " + format_endpoint(to) + " (" +
                            std::error_code(errno, std::generic_category()).message() +
                            "; a host without a broadcast route needs --discovery-address LIDAR_IP)");
    }
    const auto round_end = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    Datagram d;
    while (std::chrono::steady_clock::now() < round_end) {
      if (socket->receive(d, std::chrono::milliseconds(50)) != ReceiveStatus::datagram) continue;
      Sdk2ControlFrame frame;
      Sdk2DiscoveryAck ack;
      if (decode_sdk2_control(d.bytes.data(), d.size, frame) != Sdk2ControlStatus::ok) continue;
      if (!parse_sdk2_discovery_ack(frame, ack)) continue;  // our own broadcast request, or another frame
      const std::uint32_t address = (std::uint32_t{ack.lidar_ip[0]} << 24) | (std::uint32_t{ack.lidar_ip[1]} << 16) |
                                    (std::uint32_t{ack.lidar_ip[2]} << 8) | ack.lidar_ip[3];
      FoundLidar found{address, sdk2_serial(ack), sdk2_device_name(ack.dev_type), ack.cmd_port};
      if (lidar_matches(o.lidars, found.serial, found.address)) return found;
      const std::string name = found.serial + " (" + format_address(address) + ")";
      if (std::find(others.begin(), others.end(), name) == others.end()) {
        others.push_back(name);
        if (o.notes) *o.notes << "streamclust: live: discovery found " << found.model << " " << name << ", not chosen by --lidar\n";
      }
    }
    ++seq;
  }
  throw ConnectionError("SDK2 discovery: no " + std::string(o.lidars.empty() ? "LiDAR" : "chosen LiDAR") +
                        " answered requests to " + format_endpoint(to) + " within " +
                        std::to_string(std::chrono::duration_cast<std::chrono::seconds>(o.timeout).count()) + " s" +
                        (others.empty() ? "" : " (answered: " + comma_list(others) + ")"));
}

struct Sdk2ConfigureOptions {
  std::uint32_t host_address = 0;  ///< the host address the LiDAR sends to (0: the interface that reaches it)
  /// The host's point port; the IMU goes to point_port + 100, the status
  /// push to point_port - 100, and commands leave from point_port - 200.
  std::uint16_t point_port = 56301;
  std::optional<std::uint8_t> data_type;  ///< point data type 1, 2 or 3 (none: unchanged)
  bool work_mode_sampling = false;        ///< also set the work mode to sampling
  std::ostream* notes = nullptr;          ///< where the LiDAR now streams (null: not said)
};

/// SDK2 configure: points `lidar`'s point, IMU and status streams at this
/// host's ports (and sets the data type and work mode when asked); checks
/// the ACK (3 tries, 500 ms each). Returns the host address the LiDAR now
/// sends to.
inline std::uint32_t configure_sdk2(const FoundLidar& lidar, const Sdk2ConfigureOptions& o) {
  const std::uint32_t host = o.host_address != 0 ? o.host_address : local_address_towards(lidar.address);
  if (host == 0) throw ConnectionError("SDK2 configure: no route to the LiDAR at " + format_address(lidar.address));
  const std::uint16_t point_port = o.point_port;
  const std::uint16_t command_port = static_cast<std::uint16_t>(point_port - 200);
  const Endpoint local{host, command_port};
  auto socket = bind_or_fail(local, "SDK2 configure: cannot bind the command port " + format_endpoint(local));
  auto destination = [&](std::uint16_t host_port, std::uint16_t lidar_port) {
    Sdk2HostIpInfo info;
    info.host_ip = {static_cast<std::uint8_t>(host >> 24), static_cast<std::uint8_t>(host >> 16),
                    static_cast<std::uint8_t>(host >> 8), static_cast<std::uint8_t>(host)};
    info.host_port = host_port;
    info.lidar_port = lidar_port;
    return info;
  };
  const Sdk2Ports& p = sdk2_mid360_ports;
  Sdk2ParameterList parameters;
  parameters.add_destination(sdk2_key_push_destination, destination(static_cast<std::uint16_t>(point_port - 100), p.lidar_push));
  parameters.add_destination(sdk2_key_point_destination, destination(point_port, p.lidar_points));
  parameters.add_destination(sdk2_key_imu_destination, destination(static_cast<std::uint16_t>(point_port + 100), p.lidar_imu));
  if (o.data_type) parameters.add_u8(sdk2_key_point_data_type, *o.data_type);
  if (o.work_mode_sampling) parameters.add_work_mode(Sdk2WorkMode::sampling);
  const Endpoint to{lidar.address, lidar.command_port};
  std::vector<std::uint8_t> request;
  for (std::uint32_t attempt = 0; attempt < 3; ++attempt) {
    const std::uint32_t seq = 100 + attempt;
    encode_sdk2_set_parameters(seq, parameters, request);
    if (!socket->send_to(to, request.data(), request.size()))
      throw ConnectionError("SDK2 configure: cannot send to " + format_endpoint(to));
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
    Datagram d;
    while (std::chrono::steady_clock::now() < until) {
      if (socket->receive(d, std::chrono::milliseconds(50)) != ReceiveStatus::datagram) continue;
      Sdk2ControlFrame frame;
      Sdk2SetParametersAck ack;
      if (decode_sdk2_control(d.bytes.data(), d.size, frame) != Sdk2ControlStatus::ok) continue;
      if (frame.seq != seq || !parse_sdk2_set_parameters_ack(frame, ack)) continue;
      if (ack.ret_code != sdk2_ret_success) {
        throw ConnectionError("SDK2 configure: " + lidar.serial + " (" + format_address(lidar.address) +
                              ") refused key 0x" + std::to_string(ack.error_key) + " with return code " +
                              std::to_string(ack.ret_code) +
                              (ack.ret_code == sdk2_ret_needs_reboot ? " (needs a reboot)" : ""));
      }
      if (o.notes) {
        *o.notes << "streamclust: live: " << lidar.model << " " << lidar.serial << " at " << format_address(lidar.address)
                 << " streams to " << format_address(host) << ":" << point_port << " (points) and :" << point_port + 100
                 << " (IMU)\n";
      }
      return host;
    }
  }
  throw ConnectionError("SDK2 configure: " + lidar.serial + " at " + format_endpoint(to) +
                        " did not acknowledge the parameter write (3 tries, 500 ms each)");
}

}  // namespace streamclust::live
