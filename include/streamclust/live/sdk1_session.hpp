// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The host's side of an SDK1 LiDAR (Avia, Mid-40/70, Horizon, Tele-15):
/// wait for its broadcast (port 55000), handshake from the host's command
/// port to the broadcast's source, start sampling, then a heartbeat every
/// 800 ms (the LiDAR disconnects after missing them; the receiver thread's
/// tick sends them), and stop sampling and disconnect at the end.
/// Every wait is bounded; every failure is a ConnectionError naming the
/// endpoint and what did not answer. Facts and sources: docs/live.md.

#include <streamclust/live/lidar_connection.hpp>
#include <streamclust/live/livox_stream.hpp>
#include <streamclust/live/sdk1_control.hpp>
#include <streamclust/live/sdk1_packets.hpp>
#include <streamclust/live/sdk1_ports.hpp>
#include <streamclust/live/udp_socket.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace streamclust::live {

/// SDK1 point packets as LivoxStream reads them. The packets do not say
/// which device sent them: the data type's devices' firing interval spaces
/// the points (and the packets, for loss).
inline LivoxPacketFormat sdk1_packet_format() {
  LivoxPacketFormat f;
  f.decode = [](const std::uint8_t* d, std::size_t n, LivoxPacketContents& out) {
    const std::uint8_t data_type = n > 9 ? d[9] : 0;
    return decode_sdk1_packet(d, n, sdk1_nominal_firing_interval_ns(data_type), out);
  };
  f.packet_period_ns = [](const LivoxPacketSummary& s) {
    return static_cast<std::int64_t>(
        expected_sdk1_packet_period_ns(s.data_type, sdk1_nominal_firing_interval_ns(s.data_type)));
  };
  return f;
}

struct Sdk1SessionOptions {
  std::uint32_t host_address = 0;  ///< the interface to bind (0: every interface; the one that reaches the LiDAR is told)
  /// The host's broadcast-listen port; commands leave from listen_port + 500,
  /// data and IMU arrive on listen_port + 1000.
  std::uint16_t listen_port = 55000;
  /// The host's command port for this LiDAR (0: listen_port + 500); each
  /// LiDAR of a host needs its own, while they share the data port.
  std::uint16_t command_port = 0;
  std::vector<std::string> lidars;  ///< serial numbers or addresses to choose (empty: the first to broadcast)
  std::chrono::steady_clock::duration timeout = std::chrono::seconds(10);  ///< for the broadcast
  std::ostream* notes = nullptr;    ///< where the LiDAR streams (null: not said)
};

/// An SDK1 connection: the LiDAR found by its broadcast, the handshake, the
/// sampling and the heartbeat. Destruction stops sampling and disconnects.
///
/// Thread safety: `heartbeat` runs on the receiver thread (its tick); the
/// rest on the thread that owns the connection, `start_sampling` before the
/// receiver thread starts.
class Sdk1Session {
 public:
  /// Listens for a broadcast and handshakes; ConnectionError when no chosen
  /// LiDAR broadcasts or answers within `o.timeout`.
  explicit Sdk1Session(const Sdk1SessionOptions& o) {
    const Endpoint listen_at{o.host_address, o.listen_port};
    auto listener = bind_or_fail(listen_at, "SDK1: cannot listen for broadcasts on UDP " + format_endpoint(listen_at));
    const auto until = std::chrono::steady_clock::now() + o.timeout;
    Datagram d;
    std::vector<std::string> others;
    while (lidar_.address == 0) {
      if (std::chrono::steady_clock::now() >= until) {
        throw ConnectionError("SDK1: no " + std::string(o.lidars.empty() ? "LiDAR" : "chosen LiDAR") +
                              " broadcast to " + format_endpoint(listen_at) + " within " +
                              std::to_string(std::chrono::duration_cast<std::chrono::seconds>(o.timeout).count()) +
                              " s" + (others.empty() ? "" : " (heard: " + comma_list(others) + ")"));
      }
      if (listener->receive(d, std::chrono::milliseconds(50)) != ReceiveStatus::datagram) continue;
      Sdk1Frame frame;
      Sdk1Broadcast broadcast;
      if (decode_sdk1_frame(d.bytes.data(), d.size, frame) != Sdk1FrameStatus::ok) continue;
      if (!parse_sdk1_broadcast(frame, broadcast)) continue;
      FoundLidar found{d.source.address, broadcast.code(), sdk1_device_name(broadcast.device_type), d.source.port};
      if (lidar_matches(o.lidars, found.serial, found.address)) {
        lidar_ = found;
      } else if (std::find(others.begin(), others.end(), found.serial) == others.end()) {
        others.push_back(found.serial);
      }
    }
    host_ = o.host_address != 0 ? o.host_address : local_address_towards(lidar_.address);
    if (host_ == 0) throw ConnectionError("SDK1: no route to the LiDAR at " + format_address(lidar_.address));
    data_port_ = static_cast<std::uint16_t>(o.listen_port + 1000);
    const Endpoint command_at{host_, o.command_port != 0 ? o.command_port : static_cast<std::uint16_t>(o.listen_port + 500)};
    command_ = bind_or_fail(command_at, "SDK1: cannot bind the command port " + format_endpoint(command_at));
    to_ = Endpoint{lidar_.address, lidar_.command_port};

    Sdk1Handshake handshake;
    handshake.host_ip = {static_cast<std::uint8_t>(host_ >> 24), static_cast<std::uint8_t>(host_ >> 16),
                         static_cast<std::uint8_t>(host_ >> 8), static_cast<std::uint8_t>(host_)};
    handshake.data_port = data_port_;
    handshake.command_port = command_at.port;
    handshake.sensor_port = data_port_;
    std::vector<std::uint8_t> frame;
    request(sdk1_handshake, [&](std::uint16_t seq) { encode_sdk1_handshake(seq, handshake, frame); }, frame,
            "the handshake");
    if (o.notes) {
      *o.notes << "streamclust: live: " << lidar_.model << " " << lidar_.serial << " at " << format_address(lidar_.address)
               << " streams to " << format_address(host_) << ":" << data_port_ << "\n";
    }
  }

  /// Starts sampling (call once the data port is bound: the LiDAR streams
  /// at once).
  void start_sampling() {
    std::vector<std::uint8_t> frame;
    request(sdk1_sampling, [&](std::uint16_t seq) { encode_sdk1_request(seq, sdk1_sampling, 1, frame); }, frame,
            "start sampling");
    last_ack_ = std::chrono::steady_clock::now();
  }

  ~Sdk1Session() {
    // Stop sampling and say goodbye; a LiDAR that is gone does not answer.
    std::vector<std::uint8_t> frame;
    encode_sdk1_request(next_seq(), sdk1_sampling, 0, frame);
    command_->send_to(to_, frame.data(), frame.size());
    encode_sdk1_request(next_seq(), sdk1_disconnect, frame);
    command_->send_to(to_, frame.data(), frame.size());
  }
  Sdk1Session(const Sdk1Session&) = delete;
  Sdk1Session& operator=(const Sdk1Session&) = delete;

  const FoundLidar& lidar() const { return lidar_; }
  /// Where the LiDAR sends points and IMU samples.
  Endpoint data_endpoint() const { return Endpoint{host_, data_port_}; }

  /// The receiver thread's tick: a heartbeat every 800 ms; reads the ACKs.
  void heartbeat(std::chrono::steady_clock::time_point now) {
    Datagram d;
    while (command_->receive_ready(d) == ReceiveStatus::datagram) {
      Sdk1Frame frame;
      Sdk1HeartbeatAck ack;
      if (decode_sdk1_frame(d.bytes.data(), d.size, frame) == Sdk1FrameStatus::ok && parse_sdk1_heartbeat_ack(frame, ack)) {
        last_ack_ = now;
        heartbeat_acks_.fetch_add(1, std::memory_order_relaxed);
      }
    }
    if (now - last_heartbeat_ < sdk1_heartbeat_period) return;
    last_heartbeat_ = now;
    encode_sdk1_request(next_seq(), sdk1_heartbeat, heartbeat_frame_);
    command_->send_to(to_, heartbeat_frame_.data(), heartbeat_frame_.size());
    heartbeats_.fetch_add(1, std::memory_order_relaxed);
  }

  std::uint64_t heartbeats() const { return heartbeats_.load(std::memory_order_relaxed); }
  std::uint64_t heartbeat_acks() const { return heartbeat_acks_.load(std::memory_order_relaxed); }

 private:
  std::uint16_t next_seq() { return seq_++; }

  // Sends what `encode(seq)` writes into `frame` until the ACK of `command`
  // comes (3 tries, 500 ms each).
  template <class Encode>
  void request(Sdk1Command command, Encode&& encode, std::vector<std::uint8_t>& frame, const char* what) {
    for (int attempt = 0; attempt < 3; ++attempt) {
      const std::uint16_t seq = next_seq();
      encode(seq);
      if (!command_->send_to(to_, frame.data(), frame.size()))
        throw ConnectionError(std::string("SDK1: cannot send ") + what + " to " + format_endpoint(to_));
      const auto until = std::chrono::steady_clock::now() + sdk1_command_timeout;
      Datagram d;
      while (std::chrono::steady_clock::now() < until) {
        if (command_->receive(d, std::chrono::milliseconds(50)) != ReceiveStatus::datagram) continue;
        Sdk1Frame reply;
        std::uint8_t ret = 0;
        if (decode_sdk1_frame(d.bytes.data(), d.size, reply) != Sdk1FrameStatus::ok) continue;
        if (reply.seq != seq || !parse_sdk1_ack(reply, command, ret)) continue;
        if (ret != sdk1_success) {
          throw ConnectionError(std::string("SDK1: ") + lidar_.serial + " refused " + what + " (return code " +
                                std::to_string(ret) + ")");
        }
        return;
      }
    }
    throw ConnectionError(std::string("SDK1: ") + lidar_.serial + " at " + format_endpoint(to_) +
                          " did not acknowledge " + what + " (3 tries, 500 ms each)");
  }

  FoundLidar lidar_;
  std::uint32_t host_ = 0;
  std::uint16_t data_port_ = 0;
  std::unique_ptr<UdpSocket> command_;
  Endpoint to_;
  std::uint16_t seq_ = 1;
  std::chrono::steady_clock::time_point last_heartbeat_{}, last_ack_{};
  std::vector<std::uint8_t> heartbeat_frame_;
  std::atomic<std::uint64_t> heartbeats_{0}, heartbeat_acks_{0};
};

}  // namespace streamclust::live
