// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The device side of the Livox protocols, for tests, benchmarks and users
/// without hardware (`streamclust replay --to`): a stream of points sent as
/// a LiDAR sends them, at its rate or faster, with faults on demand.
/// - SDK2 (Mid-360): point packets of 96 slots from port 56300 (data type
///   1, 2 or 3; udp_cnt counting and wrapping; CRC-32 left 0 as real point
///   packets have it), IMU packets from 56400 (200 Hz, CRC filled).
///   Passive: it streams to the destination given. Configured: it answers
///   discovery (0x0000) on 56000 and a parameter write (0x0100) on 56100,
///   then streams to the destinations written.
/// - SDK1 (Avia and kin): it broadcasts its MSG once a second to the
///   host's listen port, answers the handshake, start/stop sampling and
///   heartbeats on its command port (65000), streams to the handshake's data
///   port, and stops when heartbeats stay away for 3 s.
/// Faults: drop, duplicate or swap packets with given probabilities, send
/// damaged datagrams in place of some (truncated, a wrong length, an unknown
/// data type, a wrong CRC, oversize), jump the device clock, reboot (clock
/// from 0 and counter reset), start the SDK2 packet counter anywhere (near
/// 65535 it wraps early).
///
/// Not thread-safe; one emulator per thread.

#include "cli/live.hpp"
#include <streamclust/live/lidar_connection.hpp>

#include <streamclust/io/record.hpp>
#include <streamclust/live/sdk1_control.hpp>
#include <streamclust/live/sdk1_packets.hpp>
#include <streamclust/live/sdk1_ports.hpp>
#include <streamclust/live/sdk2_control.hpp>
#include <streamclust/live/sdk2_device.hpp>
#include <streamclust/live/sdk2_packets.hpp>
#include <streamclust/live/udp_socket.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace streamclust::cli {

struct EmulatorOptions {
  LivoxSourceUrl target;                 ///< the host side: where to stream (SDK2) or broadcast (SDK1)
  std::uint32_t device_address = 0;      ///< the emulated LiDAR's address (0: chosen by the OS)
  std::string serial = "EMULATED0000001";
  std::optional<std::uint8_t> data_type; ///< empty: the protocol's default (SDK2 1, SDK1 2)
  double speed = 1.0;                    ///< x the recorded rate; 0: as fast as possible
  bool wait_for_configure = false;       ///< SDK2: stream only after a host's parameter write
  double drop = 0.0, duplicate = 0.0, swap = 0.0;  ///< per point packet probabilities
  double corrupt = 0.0;                  ///< per point packet: a damaged datagram is sent instead
  std::uint16_t first_counter = 0;       ///< SDK2: udp_cnt of the first point packet
  std::uint64_t seed = 1;
  std::optional<double> reboot_at;       ///< [s of stream]: clock restarts at 0, counter at 0
  std::optional<std::pair<double, double>> clock_jump;  ///< at [s of stream], by [s]
  live::LivoxTimeSync sync = live::LivoxTimeSync::none;
  std::optional<std::array<double, 2>> imu_mount;  ///< roll, pitch [deg]: send a resting IMU's samples
  std::chrono::milliseconds connect_timeout{10000};
};

struct EmulatorCounters {
  std::uint64_t packets = 0, returns = 0, dropped = 0, duplicated = 0, swapped = 0, imu_packets = 0;
  std::uint64_t corrupted = 0;           ///< point packets sent damaged (oversize ones included)
  std::uint64_t corrupted_returns = 0;   ///< the returns those packets held
  std::uint64_t oversize = 0;            ///< of the corrupted: longer than any Livox packet
};

class LivoxEmulator {
 public:
  explicit LivoxEmulator(const EmulatorOptions& o) : o_(o), random_(o.seed), counter_(o.first_counter) {
    sdk2_ = o.target.protocol == LivoxProtocol::sdk2;
    data_type_ = o.data_type.value_or(sdk2_ ? 1 : 2);
    if (sdk2_) {
      const auto& p = live::sdk2_mid360_ports;
      points_ = live::bind_or_fail({o.device_address, p.lidar_points}, "emulator: cannot bind the point port");
      imu_ = live::bind_or_fail({o.device_address, p.lidar_imu}, "emulator: cannot bind the IMU port");
      points_to_ = {target_address(), o.target.port};
      imu_to_ = {target_address(), static_cast<std::uint16_t>(o.target.port + 100)};
    } else {
      command_ = live::bind_or_fail({o.device_address, live::sdk1_lidar_command_port}, "emulator: cannot bind the command port");
      points_ = live::bind_or_fail({o.device_address, 0}, "emulator: cannot bind the data port");
      imu_ = nullptr;
    }
  }

  /// Waits for the host (SDK2 configure, SDK1 handshake and sampling);
  /// NetworkError when none comes within the connect timeout.
  void connect() {
    const auto until = std::chrono::steady_clock::now() + o_.connect_timeout;
    if (sdk2_) {
      if (!o_.wait_for_configure) return;
      const auto& p = live::sdk2_mid360_ports;
      auto discovery = live::bind_or_fail({o_.device_address, p.discovery}, "emulator: cannot bind the discovery port");
      command_ = live::bind_or_fail({o_.device_address, p.lidar_command}, "emulator: cannot bind the command port");
      while (!configured_) {
        if (std::chrono::steady_clock::now() >= until)
          throw NetworkError("emulator: no host configured the SDK2 device within the timeout");
        answer_sdk2(*discovery, std::chrono::milliseconds(20));
        answer_sdk2(*command_, std::chrono::milliseconds(20));
      }
      return;
    }
    auto last_broadcast = std::chrono::steady_clock::time_point{};
    std::vector<std::uint8_t> frame;
    const live::Endpoint broadcast_to{target_address(), o_.target.port};
    while (!sampling_) {
      const auto now = std::chrono::steady_clock::now();
      if (now >= until) throw NetworkError("emulator: no host handshook with the SDK1 device within the timeout");
      if (now - last_broadcast >= std::chrono::seconds(1)) {
        last_broadcast = now;
        live::Sdk1Broadcast b;
        std::copy_n(o_.serial.begin(), std::min<std::size_t>(o_.serial.size(), 16), b.broadcast_code.begin());
        b.device_type = 7;  // Avia
        live::encode_sdk1_broadcast(seq1_++, b, frame);
        command_->send_to(broadcast_to, frame.data(), frame.size());
      }
      answer_sdk1(std::chrono::milliseconds(20));
    }
  }

  /// Sends `records` (stream times [s], any origin; the first call's first
  /// record starts the stream) as packets at the device's pace. Returns
  /// false when the host went away (SDK1: stopped sampling, disconnected or
  /// stopped its heartbeats).
  bool send(const std::vector<io::Record>& records) {
    for (const io::Record& r : records) {
      if (!std::isfinite(r.t)) continue;
      // A ray without a return is an empty slot (0,0,0), as a device sends
      // it: the packets keep their pace and the host sees no gap.
      const bool returned = std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.z);
      if (!started_) {
        started_ = true;
        t0_ = r.t;
        wall0_ = std::chrono::steady_clock::now();
      }
      live::LivoxReturn ret;
      ret.x = returned ? r.x : 0.0f;
      ret.y = returned ? r.y : 0.0f;
      ret.z = returned ? r.z : 0.0f;
      ret.reflectivity = static_cast<std::uint8_t>(std::clamp(r.intensity, 0.0f, 255.0f));
      ret.time_ns = device_time(r.t);
      if (!pending_.empty() && (packet_full(ret) || (sdk2_ && !fill_sdk2_gap(ret)))) {
        if (!emit()) return false;
        if (!sdk2_ && !send_sdk1_empty_packets(ret)) return false;
      }
      if (pending_.empty()) pending_since_ = r.t - t0_;
      pending_.push_back(ret);
    }
    return true;
  }

  /// Sends what is pending (a last partial packet).
  bool finish() {
    if (!pending_.empty() && !emit()) return false;
    if (held_) send_datagram(*held_);
    held_.reset();
    return true;
  }

  const EmulatorCounters& counters() const { return counters_; }

  /// The point data type sent (a host's parameter write may change it).
  std::uint8_t data_type() const { return data_type_; }
  /// The work mode a host's parameter write asked for (SDK2), if any.
  std::optional<std::uint8_t> work_mode() const { return work_mode_; }

 private:
  std::uint32_t target_address() const {
    return o_.target.host_address != 0 ? o_.target.host_address : 0x7F000001u;
  }

  // Device time of stream time t [ns]: a boot offset (1 s) plus the time
  // since the first record, with the jumps and the reboot applied.
  std::uint64_t device_time(double t) {
    const double since = t - t0_;
    std::int64_t ns = 1'000'000'000 + static_cast<std::int64_t>(std::llround(since * 1e9));
    if (o_.sync != live::LivoxTimeSync::none) ns += 1'700'000'000'000'000'000;  // a synchronised clock: Unix time
    if (o_.clock_jump && since >= o_.clock_jump->first) ns += static_cast<std::int64_t>(o_.clock_jump->second * 1e9);
    if (o_.reboot_at && since >= *o_.reboot_at) {
      ns -= static_cast<std::int64_t>(std::llround(*o_.reboot_at * 1e9)) + 1'000'000'000 - 20'000'000;  // 20 ms after boot
      if (!rebooted_) {
        rebooted_ = true;
        counter_ = 0;
        imu_counter_ = 0;
      }
    }
    return static_cast<std::uint64_t>(std::max<std::int64_t>(ns, 0));
  }

  // SDK2 slots are equally spaced over a packet's time_interval, so a gap
  // of k steps before `next` (rays without a return that a recording left
  // out) becomes k - 1 empty slots, as the device sends them. False: the
  // gap is no whole number of steps (within 0.5 us) or does not fit, and
  // the packet ends before `next`.
  bool fill_sdk2_gap(const live::LivoxReturn& next) {
    const std::size_t n = pending_.size();
    if (n < 2) return true;
    const double step = static_cast<double>(pending_.back().time_ns - pending_.front().time_ns) / static_cast<double>(n - 1);
    const double gap = static_cast<double>(next.time_ns) - static_cast<double>(pending_.back().time_ns);
    if (!(step > 0.0)) return false;
    const double k = std::round(gap / step);
    if (k < 1.0 || std::abs(gap - k * step) > 500.0 || n + static_cast<std::size_t>(k) > 96) return false;
    const live::LivoxReturn last = pending_.back();
    for (int j = 1; j < static_cast<int>(k); ++j) {
      live::LivoxReturn empty;  // (0,0,0): no return
      empty.time_ns = last.time_ns + static_cast<std::uint64_t>(std::llround(j * step));
      pending_.push_back(empty);
    }
    return true;
  }

  // SDK1 packets follow each other every packet period, so a gap of whole
  // periods before `next` (a recording left out rays without a return) is
  // sent as packets of empty slots, as the device sends them. A gap above
  // kLongestScanGap is a clock jump: nothing is filled. False: the host
  // went away.
  bool send_sdk1_empty_packets(const live::LivoxReturn& next) {
    constexpr std::uint64_t kLongestScanGap = 50'000'000;  // [ns]
    const io::LivoxDataType* type = io::find_sdk1_data_type(data_type_);
    const std::uint64_t period = std::uint64_t{live::sdk1_nominal_firing_interval_ns(data_type_)} * type->structs_per_package;
    if (next.time_ns < last_packet_ns_ || next.time_ns - last_packet_ns_ > kLongestScanGap) return true;
    const double since = pending_since_;  // [s] of the packet just sent
    const std::uint64_t sent_ns = last_packet_ns_;
    while (next.time_ns >= last_packet_ns_ + period + period / 2) {
      live::LivoxReturn empty;  // (0,0,0): no return
      empty.time_ns = last_packet_ns_ + period;
      pending_since_ = since + static_cast<double>(empty.time_ns - sent_ns) * 1e-9;
      pending_.push_back(empty);
      if (!emit()) return false;
    }
    return true;
  }

  bool packet_full(const live::LivoxReturn& next) const {
    if (sdk2_) return pending_.size() >= 96 || next.time_ns < pending_.front().time_ns;
    const io::LivoxDataType* type = io::find_sdk1_data_type(data_type_);
    const std::uint64_t interval = live::sdk1_nominal_firing_interval_ns(data_type_);
    const std::uint64_t span = interval * type->structs_per_package;
    return next.time_ns + interval / 2 >= pending_.front().time_ns + span || next.time_ns < pending_.front().time_ns ||
           pending_.size() >= static_cast<std::size_t>(type->structs_per_package) * type->returns;
  }

  // Encodes the pending returns as one packet, paces, applies the faults.
  bool emit() {
    std::vector<std::uint8_t> bytes;
    const std::uint64_t first = pending_.front().time_ns;
    last_packet_ns_ = first;
    if (sdk2_) {
      live::Sdk2PacketFields f;
      f.udp_cnt = counter_++;
      f.timestamp_ns = first;
      const std::uint64_t span = pending_.back().time_ns - first;
      f.time_interval = static_cast<std::uint16_t>(std::min<std::uint64_t>((span + 50) / 100, 65535));
      f.time_sync = o_.sync;
      live::encode_sdk2_point_packet(f, static_cast<live::Sdk2DataType>(data_type_), pending_.data(),
                                     pending_.size(), bytes);
    } else {
      live::Sdk1PacketHeader h;
      h.data_type = data_type_;
      live::set_sdk1_packet_time(h, sdk1_timestamp_type(), first);
      live::encode_sdk1_data_packet(h, live::sdk1_nominal_firing_interval_ns(data_type_), pending_.data(),
                                    pending_.size(), bytes);
    }
    const auto returns = static_cast<std::uint64_t>(std::count_if(pending_.begin(), pending_.end(), [](const live::LivoxReturn& r) {
      return r.x != 0.0f || r.y != 0.0f || r.z != 0.0f;  // (0,0,0): an empty slot
    }));
    counters_.returns += returns;
    pending_.clear();
    pace();
    if (!keep_host()) return false;
    send_imu_until(first);
    ++counters_.packets;
    std::uniform_real_distribution<double> u(0.0, 1.0);
    if (u(random_) < o_.drop) {
      ++counters_.dropped;
      return true;
    }
    if (o_.corrupt > 0.0 && u(random_) < o_.corrupt) {
      damage(bytes);
      counters_.corrupted_returns += returns;
    }
    if (held_) {  // the swapped packet goes after this one
      send_datagram(bytes);
      send_datagram(*held_);
      held_.reset();
      return true;
    }
    if (u(random_) < o_.swap) {
      held_ = bytes;
      ++counters_.swapped;
      return true;
    }
    send_datagram(bytes);
    if (u(random_) < o_.duplicate) {
      send_datagram(bytes);
      ++counters_.duplicated;
    }
    return true;
  }

  // Damages a packet so that no receiver can take it for a valid one, in
  // turn: cut inside the header, 4 bytes more than its length, an unknown
  // data type, a wrong CRC (SDK2; SDK1 has none: a reserved timestamp
  // type), padded beyond any Livox packet (2000 bytes).
  void damage(std::vector<std::uint8_t>& bytes) {
    switch (counters_.corrupted++ % 5) {
      case 0: bytes.resize(16); break;
      case 1: bytes.insert(bytes.end(), 4, 0); break;
      case 2: bytes[sdk2_ ? 10 : 9] = 0x7F; break;
      case 3:
        if (sdk2_) {  // the CRC of the packet as it was, then one byte changed
          const std::uint32_t crc = live::crc32_iso_hdlc(bytes.data() + 28, bytes.size() - 28);
          for (std::size_t i = 0; i < 4; ++i) bytes[24 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
          bytes.back() ^= 0xFF;
        } else {
          bytes[8] = 2;
        }
        break;
      default:
        bytes.resize(2000, 0);
        ++counters_.oversize;
        break;
    }
  }

  // The SDK1 timestamp type of the clock's sync: 0 none, 1 PTP, 3 GPS (UTC).
  std::uint8_t sdk1_timestamp_type() const {
    return o_.sync == live::LivoxTimeSync::ptp ? 1 : o_.sync == live::LivoxTimeSync::gps ? 3 : 0;
  }

  // Sends a packet when the device would: its first point's stream time,
  // scaled by the speed, after the first packet.
  void pace() const {
    if (o_.speed <= 0.0) return;
    const auto due = wall0_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                  std::chrono::duration<double>(pending_since_ / o_.speed));
    std::this_thread::sleep_until(due);
  }

  void send_datagram(const std::vector<std::uint8_t>& bytes) {
    points_->send_to(points_to_, bytes.data(), bytes.size());
  }

  // IMU packets at 200 Hz of device time up to `until_ns`.
  void send_imu_until(std::uint64_t until_ns) {
    if (!o_.imu_mount) return;
    if (next_imu_ns_ == 0 || until_ns + 1'000'000'000 < next_imu_ns_) next_imu_ns_ = until_ns;  // start or reboot
    constexpr double deg = 3.14159265358979323846 / 180.0;
    const double roll = (*o_.imu_mount)[0] * deg, pitch = (*o_.imu_mount)[1] * deg;
    live::LivoxImuSample s;
    // up = (-sin pitch, sin roll cos pitch, cos roll cos pitch): the resting
    // accelerometer's reading [g] (imu_gravity.hpp).
    s.acceleration = {static_cast<float>(-std::sin(pitch)), static_cast<float>(std::sin(roll) * std::cos(pitch)),
                      static_cast<float>(std::cos(roll) * std::cos(pitch))};
    std::vector<std::uint8_t> bytes;
    while (next_imu_ns_ <= until_ns) {
      if (sdk2_) {
        live::Sdk2PacketFields f;
        f.udp_cnt = imu_counter_++;
        f.timestamp_ns = next_imu_ns_;
        f.time_sync = o_.sync;
        f.fill_crc = true;
        live::encode_sdk2_imu_packet(f, s, bytes);
        imu_->send_to(imu_to_, bytes.data(), bytes.size());
      } else {
        live::Sdk1PacketHeader h;
        live::set_sdk1_packet_time(h, sdk1_timestamp_type(), next_imu_ns_);
        live::encode_sdk1_imu_packet(h, s, bytes);
        points_->send_to(imu_to_, bytes.data(), bytes.size());
      }
      ++counters_.imu_packets;
      next_imu_ns_ += 5'000'000;
    }
  }

  // SDK1: answers commands; false once the host is gone.
  bool keep_host() {
    if (sdk2_) return true;
    answer_sdk1(std::chrono::milliseconds(0));
    if (std::chrono::steady_clock::now() - last_heartbeat_ > live::sdk1_disconnect_timeout) sampling_ = false;
    return sampling_;
  }

  void answer_sdk1(std::chrono::milliseconds wait) {
    live::Datagram d;
    while (command_->receive(d, wait) == live::ReceiveStatus::datagram) {
      wait = std::chrono::milliseconds(0);
      live::Sdk1Frame frame;
      if (live::decode_sdk1_frame(d.bytes.data(), d.size, frame) != live::Sdk1FrameStatus::ok) continue;
      std::vector<std::uint8_t> reply;
      live::Sdk1Handshake hs;
      if (live::parse_sdk1_handshake(frame, hs)) {
        const std::uint32_t host = (std::uint32_t{hs.host_ip[0]} << 24) | (std::uint32_t{hs.host_ip[1]} << 16) |
                                   (std::uint32_t{hs.host_ip[2]} << 8) | hs.host_ip[3];
        points_to_ = {host, hs.data_port};
        imu_to_ = {host, hs.sensor_port};
        live::encode_sdk1_ack(frame.seq, live::sdk1_handshake, live::sdk1_success, reply);
        last_heartbeat_ = std::chrono::steady_clock::now();
      } else if (live::is_sdk1_request(frame, live::sdk1_heartbeat)) {
        live::Sdk1HeartbeatAck ack;
        ack.state = sampling_ ? 1 : 0;
        live::encode_sdk1_heartbeat_ack(frame.seq, ack, reply);
        last_heartbeat_ = std::chrono::steady_clock::now();
      } else if (live::is_sdk1_request(frame, live::sdk1_sampling)) {
        sampling_ = frame.data_size >= 1 && frame.data[0] == 1;
        live::encode_sdk1_ack(frame.seq, live::sdk1_sampling, live::sdk1_success, reply);
        last_heartbeat_ = std::chrono::steady_clock::now();
      } else if (live::is_sdk1_request(frame, live::sdk1_disconnect)) {
        sampling_ = false;
        live::encode_sdk1_ack(frame.seq, live::sdk1_disconnect, live::sdk1_success, reply);
      } else {
        continue;
      }
      command_->send_to(d.source, reply.data(), reply.size());
    }
  }

  void answer_sdk2(live::UdpSocket& socket, std::chrono::milliseconds wait) {
    live::Datagram d;
    if (socket.receive(d, wait) != live::ReceiveStatus::datagram) return;
    live::Sdk2ControlFrame frame;
    if (live::decode_sdk2_control(d.bytes.data(), d.size, frame) != live::Sdk2ControlStatus::ok) return;
    if (frame.cmd_type != live::Sdk2CommandType::request) return;
    std::vector<std::uint8_t> reply;
    if (frame.cmd_id == live::sdk2_cmd_discovery) {
      live::Sdk2DiscoveryAck ack;
      ack.dev_type = live::sdk2_device_mid360;
      std::copy_n(o_.serial.begin(), std::min<std::size_t>(o_.serial.size(), 16), ack.serial.begin());
      const std::uint32_t me = o_.device_address != 0 ? o_.device_address : 0x7F000001u;
      ack.lidar_ip = {static_cast<std::uint8_t>(me >> 24), static_cast<std::uint8_t>(me >> 16),
                      static_cast<std::uint8_t>(me >> 8), static_cast<std::uint8_t>(me)};
      ack.cmd_port = live::sdk2_mid360_ports.lidar_command;
      live::encode_sdk2_discovery_ack(frame.seq, ack, reply);
    } else if (frame.cmd_id == live::sdk2_cmd_set_parameters) {
      std::vector<live::Sdk2KeyValue> pairs;
      live::Sdk2SetParametersAck ack;
      if (live::parse_sdk2_parameters(frame.data, frame.data_size, pairs) != live::Sdk2ParameterStatus::ok) {
        ack.ret_code = 1;
      }
      for (const live::Sdk2KeyValue& kv : pairs) {
        live::Sdk2HostIpInfo info;
        std::uint8_t value = 0;
        if ((kv.key == live::sdk2_key_point_destination || kv.key == live::sdk2_key_imu_destination) &&
            live::parse_sdk2_destination(kv, info)) {
          const live::Endpoint to{(std::uint32_t{info.host_ip[0]} << 24) | (std::uint32_t{info.host_ip[1]} << 16) |
                                      (std::uint32_t{info.host_ip[2]} << 8) | info.host_ip[3],
                                  info.host_port};
          (kv.key == live::sdk2_key_point_destination ? points_to_ : imu_to_) = to;
        } else if (kv.key == live::sdk2_key_point_data_type && live::parse_sdk2_u8(kv, value)) {
          if (value >= 1 && value <= 3) data_type_ = value;
        } else if (kv.key == live::sdk2_key_work_mode && live::parse_sdk2_u8(kv, value)) {
          work_mode_ = value;
        }
      }
      live::encode_sdk2_set_parameters_ack(frame.seq, ack, reply);
      configured_ = ack.ret_code == live::sdk2_ret_success;
    } else {
      return;
    }
    socket.send_to(d.source, reply.data(), reply.size());
  }

  EmulatorOptions o_;
  bool sdk2_ = true;
  std::uint8_t data_type_ = 1;  // may change by a host's parameter write (SDK2)
  std::optional<std::uint8_t> work_mode_;  // written by a host (SDK2)
  std::mt19937_64 random_;
  std::unique_ptr<live::UdpSocket> points_, imu_, command_;
  live::Endpoint points_to_, imu_to_;
  bool configured_ = false, sampling_ = false, started_ = false, rebooted_ = false;
  std::chrono::steady_clock::time_point last_heartbeat_{}, wall0_{};
  double t0_ = 0.0, pending_since_ = 0.0;  // [s]
  std::uint16_t counter_ = 0, imu_counter_ = 0, seq1_ = 1;
  std::uint64_t next_imu_ns_ = 0;
  std::uint64_t last_packet_ns_ = 0;  // device time of the last packet sent [ns]
  std::vector<live::LivoxReturn> pending_;
  std::optional<std::vector<std::uint8_t>> held_;
  EmulatorCounters counters_;
};

}  // namespace streamclust::cli
