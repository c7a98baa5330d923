// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// LivoxConnection: the LiDARs of one live source, connected and heard.
/// From a source string's protocol, host and port and the LiDARs chosen by
/// serial number or address it does what the Livox SDKs do, one LiDAR after
/// another:
/// - SDK2: a LiDAR given by address is heard passively; one given by serial
///   number (or any with `configure`) is found by discovery, and with
///   `configure` its point and IMU streams are pointed at this host;
/// - SDK1: broadcast, handshake (each LiDAR from its own command port, port
///   + 500 + k), sampling started by `start`, heartbeats from the receiver
///   thread; all stream to the one data port (port + 1000).
/// It then binds the receiver (<streamclust/live/livox_receiver.hpp>), one
/// queue per LiDAR. The command-line tool and the Python module connect
/// through it. Facts and sources: docs/live.md.
///
/// Thread safety: construct, `start` and `stop` from one thread; the
/// receiver's queues follow LivoxReceiver's rules.

#include <streamclust/live/lidar_connection.hpp>
#include <streamclust/live/livox_receiver.hpp>
#include <streamclust/live/livox_source.hpp>
#include <streamclust/live/sdk1_session.hpp>
#include <streamclust/live/sdk2_session.hpp>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <system_error>
#include <vector>

namespace streamclust::live {

/// SDK1 LiDARs of one connection: each commands from its own port between
/// the listen port + 500 and the data port at + 1000.
inline constexpr std::size_t kMaxSdk1Lidars = 16;

struct LivoxConnectionOptions {
  LivoxSourceUrl source;
  std::vector<std::string> lidars;  ///< serial numbers or addresses, one engine each (empty: the first heard)
  bool configure = false;           ///< SDK2: discovery, then point each LiDAR's streams at this host
  std::optional<std::uint32_t> discovery_address;  ///< where SDK2 discovery requests go (default broadcast)
  std::optional<std::uint8_t> data_type;            ///< SDK2 configure: point data type 1-3 (none: unchanged)
  bool work_mode_sampling = false;                  ///< SDK2 configure: also set the work mode to sampling
  std::chrono::steady_clock::duration wait = std::chrono::seconds(10);  ///< per discovery or handshake
  std::size_t queue_packets = 4096;                 ///< per LiDAR, receiver to engine
  std::size_t socket_buffer_bytes = 8u << 20;
  std::ostream* notes = nullptr;                    ///< where the connection steps are said (null: nowhere)
};

class LivoxConnection {
 public:
  /// Finds, configures or shakes hands with every chosen LiDAR and binds
  /// the receiver; ConnectionError when a LiDAR does not answer within
  /// `o.wait` or a port cannot be bound; std::invalid_argument for more
  /// than kMaxSdk1Lidars SDK1 LiDARs.
  explicit LivoxConnection(const LivoxConnectionOptions& o) {
    const std::vector<std::string> chosen = o.lidars.empty() ? std::vector<std::string>{""} : o.lidars;
    auto only = [](const std::string& l) { return l.empty() ? std::vector<std::string>{} : std::vector<std::string>{l}; };
    std::vector<Endpoint> ports;
    if (o.source.protocol == LivoxProtocol::sdk2) {
      std::uint32_t host = o.source.host_address;
      for (const std::string& l : chosen) {
        const auto address = parse_address(l);
        if (l.empty() && !o.configure) {
          devices_.push_back(0);  // the first LiDAR heard
          names_.emplace_back();
        } else if (address && !o.configure) {
          devices_.push_back(*address);
          names_.emplace_back();
        } else {
          Sdk2DiscoveryOptions d;
          d.host_address = o.source.host_address;
          d.request_address = o.discovery_address.value_or(0xFFFFFFFFu);
          d.lidars = only(l);
          d.timeout = o.wait;
          d.notes = o.notes;
          const FoundLidar lidar = discover_sdk2(d);
          devices_.push_back(lidar.address);
          names_.push_back(lidar.model + " " + lidar.serial);
          if (o.configure) {
            Sdk2ConfigureOptions c;
            c.host_address = o.source.host_address;
            c.point_port = o.source.port;
            c.data_type = o.data_type;
            c.work_mode_sampling = o.work_mode_sampling;
            c.notes = o.notes;
            host = configure_sdk2(lidar, c);
          }
        }
      }
      ports.push_back(Endpoint{host, o.source.port});
      ports.push_back(Endpoint{host, static_cast<std::uint16_t>(o.source.port + 100)});
    } else {
      if (chosen.size() > kMaxSdk1Lidars)
        throw std::invalid_argument("lidars: at most " + std::to_string(kMaxSdk1Lidars) + " SDK1 LiDARs per source");
      for (std::size_t i = 0; i < chosen.size(); ++i) {
        Sdk1SessionOptions s;
        s.host_address = o.source.host_address;
        s.listen_port = o.source.port;
        s.command_port = static_cast<std::uint16_t>(o.source.port + 500 + i);
        s.lidars = only(chosen[i]);
        s.timeout = o.wait;
        s.notes = o.notes;
        sdk1_.push_back(std::make_unique<Sdk1Session>(s));
        names_.push_back(sdk1_.back()->lidar().model + " " + sdk1_.back()->lidar().serial);
        devices_.push_back(sdk1_.back()->lidar().address);
      }
      ports.push_back(sdk1_.front()->data_endpoint());
    }
    where_ = format_endpoint(ports.front());

    ReceiverOptions ro;
    ro.ports = ports;
    if (!(devices_.size() == 1 && devices_[0] == 0)) ro.devices = devices_;
    ro.queue_packets = o.queue_packets;
    ro.socket_buffer_bytes = o.socket_buffer_bytes;
    if (!sdk1_.empty()) {
      ro.on_tick = [this](std::chrono::steady_clock::time_point now) {
        for (auto& s : sdk1_) s->heartbeat(now);
      };
    }
    try {
      receiver_ = std::make_unique<LivoxReceiver>(ro);
    } catch (const std::system_error& e) {
      throw ConnectionError(std::string("live: ") + e.what());
    }
  }

  ~LivoxConnection() { stop(); }
  LivoxConnection(const LivoxConnection&) = delete;
  LivoxConnection& operator=(const LivoxConnection&) = delete;

  /// Starts sampling (SDK1; the data port is bound, so nothing the LiDARs
  /// send is lost) and the receiver thread.
  void start() {
    for (auto& s : sdk1_) s->start_sampling();
    receiver_->start();
  }

  /// Stops the receiver, then the LiDARs (SDK1: stop sampling and
  /// disconnect). Idempotent; within one receiver poll period (20 ms).
  void stop() {
    if (receiver_) receiver_->stop();
    sdk1_.clear();
  }

  LivoxReceiver& receiver() { return *receiver_; }
  const LivoxReceiver& receiver() const { return *receiver_; }
  /// The LiDARs, in the order chosen (one receiver queue each).
  std::size_t lidars() const { return devices_.size(); }
  /// "MODEL SERIAL" of LiDAR `i` when discovery or its broadcast named it,
  /// else "LiDAR at ADDRESS" once it sent (empty before).
  std::string lidar_name(std::size_t i) const {
    if (!names_.at(i).empty()) return names_[i];
    const std::uint32_t a = receiver_->device_address(i);
    return a == 0 ? std::string() : "LiDAR at " + format_address(a);
  }
  /// Where the points arrive (HOST:PORT).
  const std::string& endpoint() const { return where_; }

 private:
  std::vector<std::uint32_t> devices_;
  std::vector<std::string> names_;
  std::vector<std::unique_ptr<Sdk1Session>> sdk1_;
  std::unique_ptr<LivoxReceiver> receiver_;
  std::string where_;
};

}  // namespace streamclust::live
