// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The control side of `streamclust live`: what the host says to a Livox
/// LiDAR before and while it streams.
/// - SDK2 configure mode (`--configure`): discovery (0x0000, broadcast to
///   port 56000), then one parameter write (0x0100) pointing the point and
///   IMU streams at this host (keys 0x0006, 0x0007; the status push 0x0005
///   too), optionally the data type and the work mode; the ACK is checked.
///   Passive mode sends nothing: the LiDAR streams to its stored destination.
/// - SDK1: wait for the LiDAR's broadcast (port 55000), handshake from the
///   host's command port to the broadcast's source, start sampling, then a
///   heartbeat every 800 ms (the LiDAR disconnects after missing them; the
///   receiver thread's tick sends them), and stop sampling at the end.
/// Every wait is bounded and every failure is a NetworkError that names the
/// endpoint and what did not answer. Facts and sources: docs/live.md.

#include "cli/live.hpp"

#include <streamclust/live/sdk1_control.hpp>
#include <streamclust/live/sdk1_ports.hpp>
#include <streamclust/live/sdk2_control.hpp>
#include <streamclust/live/sdk2_device.hpp>
#include <streamclust/live/udp_socket.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <system_error>
#include <vector>

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

namespace streamclust::cli {

/// The address of this host's interface that reaches `remote` (the source
/// address the kernel would choose); 0 when there is no route.
inline std::uint32_t local_address_towards(std::uint32_t remote) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return 0;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(9);
  a.sin_addr.s_addr = htonl(remote);
  std::uint32_t local = 0;
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0) {
    sockaddr_in l{};
    socklen_t n = sizeof l;
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&l), &n) == 0) local = ntohl(l.sin_addr.s_addr);
  }
  ::close(fd);
  return local;
}

/// A UdpSocket bound to `at`, or a NetworkError naming it.
inline std::unique_ptr<live::UdpSocket> bind_or_fail(live::Endpoint at, const std::string& what) {
  try {
    return std::make_unique<live::UdpSocket>(at);
  } catch (const std::system_error& e) {
    throw NetworkError(what + ": " + e.what());
  }
}

/// Does `lidar` (a --lidar value: serial number or dotted address) name a
/// device with serial `serial` at `address`? Empty: any device.
inline bool lidar_matches(const std::vector<std::string>& lidars, const std::string& serial, std::uint32_t address) {
  if (lidars.empty()) return true;
  for (const std::string& l : lidars) {
    if (l == serial) return true;
    if (const auto a = live::parse_address(l); a && *a == address) return true;
  }
  return false;
}

/// One LiDAR found by discovery.
struct FoundLidar {
  std::uint32_t address = 0;
  std::string serial;
  std::string model;
  std::uint16_t command_port = 0;  ///< where its commands go (SDK2: from the ACK; SDK1: the broadcast's source port)
};

// ------------------------------------------------------------------- SDK2

/// SDK2 discovery: broadcasts 0x0000 requests (once a second) from the
/// host's discovery port and collects the ACKs until one LiDAR matching
/// `o.lidars` answers or `timeout` passes.
inline FoundLidar discover_sdk2(const LiveOptions& o, std::chrono::steady_clock::duration timeout, std::ostream& err) {
  const live::Endpoint local{o.source.host_address, live::sdk2_mid360_ports.discovery};
  auto socket = bind_or_fail(local, "SDK2 discovery: cannot listen on UDP " + live::format_endpoint(local));
  socket->enable_broadcast();
  const live::Endpoint to{o.discovery_address.value_or(0xFFFFFFFFu), live::sdk2_mid360_ports.discovery};
  std::vector<std::uint8_t> request;
  const auto until = std::chrono::steady_clock::now() + timeout;
  std::uint32_t seq = 1;
  std::vector<std::string> others;
  while (std::chrono::steady_clock::now() < until) {
    live::encode_sdk2_discovery_request(seq, request);
    if (!socket->send_to(to, request.data(), request.size())) {
      throw NetworkError("SDK2 discovery: cannot send to " + live::format_endpoint(to) + " (" +
                         std::error_code(errno, std::generic_category()).message() +
                         "; a host without a broadcast route needs --discovery-address LIDAR_IP)");
    }
    const auto round_end = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    live::Datagram d;
    while (std::chrono::steady_clock::now() < round_end) {
      if (socket->receive(d, std::chrono::milliseconds(50)) != live::ReceiveStatus::datagram) continue;
      live::Sdk2ControlFrame frame;
      live::Sdk2DiscoveryAck ack;
      if (live::decode_sdk2_control(d.bytes.data(), d.size, frame) != live::Sdk2ControlStatus::ok) continue;
      if (!live::parse_sdk2_discovery_ack(frame, ack)) continue;  // our own broadcast request, or another frame
      const std::uint32_t address = (std::uint32_t{ack.lidar_ip[0]} << 24) | (std::uint32_t{ack.lidar_ip[1]} << 16) |
                                    (std::uint32_t{ack.lidar_ip[2]} << 8) | ack.lidar_ip[3];
      FoundLidar found{address, live::sdk2_serial(ack), live::sdk2_device_name(ack.dev_type), ack.cmd_port};
      if (lidar_matches(o.lidars, found.serial, found.address)) return found;
      const std::string name = found.serial + " (" + live::format_address(address) + ")";
      if (std::find(others.begin(), others.end(), name) == others.end()) {
        others.push_back(name);
        if (!o.cluster.quiet) err << "streamclust: live: discovery found " << found.model << " " << name << ", not chosen by --lidar\n";
      }
    }
    ++seq;
  }
  std::string found_list;
  for (const std::string& s : others) found_list += (found_list.empty() ? "" : ", ") + s;
  throw NetworkError("SDK2 discovery: no " + std::string(o.lidars.empty() ? "LiDAR" : "chosen LiDAR") +
                     " answered requests to " + live::format_endpoint(to) + " within " +
                     std::to_string(std::chrono::duration_cast<std::chrono::seconds>(timeout).count()) + " s" +
                     (found_list.empty() ? "" : " (answered: " + found_list + ")"));
}

/// SDK2 configure mode: points `lidar`'s point, IMU and status streams at
/// this host's ports (and sets the data type and work mode when asked);
/// checks the ACK. Returns the host address the LiDAR now sends to.
inline std::uint32_t configure_sdk2(const LiveOptions& o, const FoundLidar& lidar, std::ostream& err) {
  const std::uint32_t host = o.source.host_address != 0 ? o.source.host_address : local_address_towards(lidar.address);
  if (host == 0) throw NetworkError("SDK2 configure: no route to the LiDAR at " + live::format_address(lidar.address));
  const std::uint16_t point_port = o.source.port;
  const std::uint16_t command_port = static_cast<std::uint16_t>(point_port - 200);
  const live::Endpoint local{host, command_port};
  auto socket = bind_or_fail(local, "SDK2 configure: cannot bind the command port " + live::format_endpoint(local));
  auto destination = [&](std::uint16_t host_port, std::uint16_t lidar_port) {
    live::Sdk2HostIpInfo info;
    info.host_ip = {static_cast<std::uint8_t>(host >> 24), static_cast<std::uint8_t>(host >> 16),
                    static_cast<std::uint8_t>(host >> 8), static_cast<std::uint8_t>(host)};
    info.host_port = host_port;
    info.lidar_port = lidar_port;
    return info;
  };
  const live::Sdk2Ports& p = live::sdk2_mid360_ports;
  live::Sdk2ParameterList parameters;
  parameters.add_destination(live::sdk2_key_push_destination,
                             destination(static_cast<std::uint16_t>(point_port - 100), p.lidar_push));
  parameters.add_destination(live::sdk2_key_point_destination, destination(point_port, p.lidar_points));
  parameters.add_destination(live::sdk2_key_imu_destination,
                             destination(static_cast<std::uint16_t>(point_port + 100), p.lidar_imu));
  if (o.data_type) parameters.add_u8(live::sdk2_key_point_data_type, *o.data_type);
  if (o.work_mode_sampling) parameters.add_work_mode(live::Sdk2WorkMode::sampling);
  const live::Endpoint to{lidar.address, lidar.command_port};
  std::vector<std::uint8_t> request;
  for (std::uint32_t attempt = 0; attempt < 3; ++attempt) {
    const std::uint32_t seq = 100 + attempt;
    live::encode_sdk2_set_parameters(seq, parameters, request);
    if (!socket->send_to(to, request.data(), request.size()))
      throw NetworkError("SDK2 configure: cannot send to " + live::format_endpoint(to));
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
    live::Datagram d;
    while (std::chrono::steady_clock::now() < until) {
      if (socket->receive(d, std::chrono::milliseconds(50)) != live::ReceiveStatus::datagram) continue;
      live::Sdk2ControlFrame frame;
      live::Sdk2SetParametersAck ack;
      if (live::decode_sdk2_control(d.bytes.data(), d.size, frame) != live::Sdk2ControlStatus::ok) continue;
      if (frame.seq != seq || !live::parse_sdk2_set_parameters_ack(frame, ack)) continue;
      if (ack.ret_code != live::sdk2_ret_success) {
        throw NetworkError("SDK2 configure: " + lidar.serial + " (" + live::format_address(lidar.address) +
                           ") refused key 0x" + std::to_string(ack.error_key) + " with return code " +
                           std::to_string(ack.ret_code) +
                           (ack.ret_code == live::sdk2_ret_needs_reboot ? " (needs a reboot)" : ""));
      }
      if (!o.cluster.quiet) {
        err << "streamclust: live: " << lidar.model << " " << lidar.serial << " at "
            << live::format_address(lidar.address) << " streams to " << live::format_address(host) << ":"
            << point_port << " (points) and :" << point_port + 100 << " (IMU)\n";
      }
      return host;
    }
  }
  throw NetworkError("SDK2 configure: " + lidar.serial + " at " + live::format_endpoint(to) +
                     " did not acknowledge the parameter write (3 tries, 500 ms each)");
}

// ------------------------------------------------------------------- SDK1

/// An SDK1 connection: the LiDAR found by its broadcast, the handshake, the
/// sampling and the heartbeat. `heartbeat` runs on the receiver thread;
/// the rest on the thread that owns the connection.
class Sdk1Session {
 public:
  /// Listens for a broadcast and handshakes; NetworkError when no chosen
  /// LiDAR broadcasts or answers within `timeout`.
  Sdk1Session(const LiveOptions& o, std::chrono::steady_clock::duration timeout, std::ostream& err) {
    const std::uint16_t listen_port = o.source.port;
    const live::Endpoint listen_at{o.source.host_address, listen_port};
    auto listener = bind_or_fail(listen_at, "SDK1: cannot listen for broadcasts on UDP " +
                                                live::format_endpoint(listen_at));
    const auto until = std::chrono::steady_clock::now() + timeout;
    live::Datagram d;
    std::vector<std::string> others;
    while (lidar_.address == 0) {
      if (std::chrono::steady_clock::now() >= until) {
        std::string list;
        for (const auto& s : others) list += (list.empty() ? "" : ", ") + s;
        throw NetworkError("SDK1: no " + std::string(o.lidars.empty() ? "LiDAR" : "chosen LiDAR") +
                           " broadcast to " + live::format_endpoint(listen_at) + " within " +
                           std::to_string(std::chrono::duration_cast<std::chrono::seconds>(timeout).count()) + " s" +
                           (list.empty() ? "" : " (heard: " + list + ")"));
      }
      if (listener->receive(d, std::chrono::milliseconds(50)) != live::ReceiveStatus::datagram) continue;
      live::Sdk1Frame frame;
      live::Sdk1Broadcast broadcast;
      if (live::decode_sdk1_frame(d.bytes.data(), d.size, frame) != live::Sdk1FrameStatus::ok) continue;
      if (!live::parse_sdk1_broadcast(frame, broadcast)) continue;
      FoundLidar found{d.source.address, broadcast.code(), live::sdk1_device_name(broadcast.device_type), d.source.port};
      if (lidar_matches(o.lidars, found.serial, found.address)) {
        lidar_ = found;
      } else if (std::find(others.begin(), others.end(), found.serial) == others.end()) {
        others.push_back(found.serial);
      }
    }
    host_ = o.source.host_address != 0 ? o.source.host_address : local_address_towards(lidar_.address);
    if (host_ == 0) throw NetworkError("SDK1: no route to the LiDAR at " + live::format_address(lidar_.address));
    data_port_ = static_cast<std::uint16_t>(listen_port + 1000);
    const live::Endpoint command_at{host_, static_cast<std::uint16_t>(listen_port + 500)};
    command_ = bind_or_fail(command_at, "SDK1: cannot bind the command port " + live::format_endpoint(command_at));
    to_ = live::Endpoint{lidar_.address, lidar_.command_port};

    live::Sdk1Handshake handshake;
    handshake.host_ip = {static_cast<std::uint8_t>(host_ >> 24), static_cast<std::uint8_t>(host_ >> 16),
                         static_cast<std::uint8_t>(host_ >> 8), static_cast<std::uint8_t>(host_)};
    handshake.data_port = data_port_;
    handshake.command_port = command_at.port;
    handshake.sensor_port = data_port_;
    std::vector<std::uint8_t> frame;
    request(live::sdk1_handshake, [&](std::uint16_t seq) { live::encode_sdk1_handshake(seq, handshake, frame); },
            frame, "the handshake");
    if (!o.cluster.quiet) {
      err << "streamclust: live: " << lidar_.model << " " << lidar_.serial << " at " << live::format_address(lidar_.address)
          << " streams to " << live::format_address(host_) << ":" << data_port_ << "\n";
    }
  }

  /// Starts sampling (call once the data port is bound: the LiDAR streams
  /// at once). Not thread-safe with `heartbeat`: call before the receiver
  /// thread runs the heartbeat.
  void start_sampling() {
    std::vector<std::uint8_t> frame;
    request(live::sdk1_sampling, [&](std::uint16_t seq) { live::encode_sdk1_request(seq, live::sdk1_sampling, 1, frame); },
            frame, "start sampling");
    last_ack_ = std::chrono::steady_clock::now();
  }

  ~Sdk1Session() {
    // Stop sampling and say goodbye; a LiDAR that is gone does not answer.
    std::vector<std::uint8_t> frame;
    live::encode_sdk1_request(next_seq(), live::sdk1_sampling, 0, frame);
    command_->send_to(to_, frame.data(), frame.size());
    live::encode_sdk1_request(next_seq(), live::sdk1_disconnect, frame);
    command_->send_to(to_, frame.data(), frame.size());
  }
  Sdk1Session(const Sdk1Session&) = delete;
  Sdk1Session& operator=(const Sdk1Session&) = delete;

  const FoundLidar& lidar() const { return lidar_; }
  /// Where the LiDAR sends points and IMU samples.
  live::Endpoint data_endpoint() const { return live::Endpoint{host_, data_port_}; }

  /// The receiver thread's tick: a heartbeat every 800 ms; reads the ACKs.
  void heartbeat(std::chrono::steady_clock::time_point now) {
    live::Datagram d;
    while (command_->receive_ready(d) == live::ReceiveStatus::datagram) {
      live::Sdk1Frame frame;
      live::Sdk1HeartbeatAck ack;
      if (live::decode_sdk1_frame(d.bytes.data(), d.size, frame) == live::Sdk1FrameStatus::ok &&
          live::parse_sdk1_heartbeat_ack(frame, ack)) {
        last_ack_ = now;
        heartbeat_acks_.fetch_add(1, std::memory_order_relaxed);
      }
    }
    if (now - last_heartbeat_ < live::sdk1_heartbeat_period) return;
    last_heartbeat_ = now;
    std::vector<std::uint8_t>& frame = heartbeat_frame_;
    live::encode_sdk1_request(next_seq(), live::sdk1_heartbeat, frame);
    command_->send_to(to_, frame.data(), frame.size());
    heartbeats_.fetch_add(1, std::memory_order_relaxed);
  }

  std::uint64_t heartbeats() const { return heartbeats_.load(std::memory_order_relaxed); }
  std::uint64_t heartbeat_acks() const { return heartbeat_acks_.load(std::memory_order_relaxed); }

 private:
  std::uint16_t next_seq() { return seq_++; }

  // Sends what `encode(seq)` writes into `frame` until the ACK of `command`
  // comes (3 tries, 500 ms each).
  template <class Encode>
  void request(live::Sdk1Command command, Encode&& encode, std::vector<std::uint8_t>& frame, const char* what) {
    for (int attempt = 0; attempt < 3; ++attempt) {
      const std::uint16_t seq = next_seq();
      encode(seq);
      if (!command_->send_to(to_, frame.data(), frame.size()))
        throw NetworkError(std::string("SDK1: cannot send ") + what + " to " + live::format_endpoint(to_));
      const auto until = std::chrono::steady_clock::now() + live::sdk1_command_timeout;
      live::Datagram d;
      while (std::chrono::steady_clock::now() < until) {
        if (command_->receive(d, std::chrono::milliseconds(50)) != live::ReceiveStatus::datagram) continue;
        live::Sdk1Frame reply;
        std::uint8_t ret = 0;
        if (live::decode_sdk1_frame(d.bytes.data(), d.size, reply) != live::Sdk1FrameStatus::ok) continue;
        if (reply.seq != seq || !live::parse_sdk1_ack(reply, command, ret)) continue;
        if (ret != live::sdk1_success) {
          throw NetworkError(std::string("SDK1: ") + lidar_.serial + " refused " + what + " (return code " +
                             std::to_string(ret) + ")");
        }
        return;
      }
    }
    throw NetworkError(std::string("SDK1: ") + lidar_.serial + " at " + live::format_endpoint(to_) +
                       " did not acknowledge " + what + " (3 tries, 500 ms each)");
  }

  FoundLidar lidar_;
  std::uint32_t host_ = 0;
  std::uint16_t data_port_ = 0;
  std::unique_ptr<live::UdpSocket> command_;
  live::Endpoint to_;
  std::uint16_t seq_ = 1;
  std::chrono::steady_clock::time_point last_heartbeat_{}, last_ack_{};
  std::vector<std::uint8_t> heartbeat_frame_;
  std::atomic<std::uint64_t> heartbeats_{0}, heartbeat_acks_{0};
};

}  // namespace streamclust::cli
