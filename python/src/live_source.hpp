// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// LiveSource: one Livox LiDAR's decoded returns as they arrive, for the
/// module's `streamclust.live`. It connects as `streamclust live` does
/// (<streamclust/live/livox_connection.hpp>: SDK2 passive, or discovery and
/// configure; SDK1 broadcast, handshake, sampling and heartbeats), runs the
/// receiver thread and decodes, orders and clocks the packets
/// (LivoxStream) on the caller's thread in `pull`. The stream ends after
/// `duration`, after `idle_exit` without packets, or when the receiver
/// fails; `close` (and destruction) stops the receiver and the LiDAR (SDK1:
/// stop sampling).
///
/// Thread safety: one thread at a time (the binding serialises calls); the
/// receiver thread only fills the queue. No Python here: callers release
/// the GIL around every call.

#include <streamclust/live/live_counters.hpp>
#include <streamclust/live/livox_connection.hpp>
#include <streamclust/live/livox_stream.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <stdexcept>
#include <thread>
#include <vector>

namespace streamclust::python {

struct LiveSourceOptions {
  /// The source, the LiDAR (one at most), configure, discovery, the wait
  /// for each connection step and for the first packet, the queue.
  live::LivoxConnectionOptions connection;
  std::string source_text;                          ///< as given, for messages
  std::chrono::steady_clock::duration duration{};   ///< of wall time from the connection; zero: none
  std::chrono::steady_clock::duration idle_exit{};  ///< without packets ends the stream; zero: never
  std::size_t reorder_packets = 8;                  ///< packets held to undo reordering
};

/// Why a live stream ended.
enum class LiveSourceEnd { running, duration, idle, receiver_failed, closed };

inline const char* describe(LiveSourceEnd e) {
  switch (e) {
    case LiveSourceEnd::running: return "running";
    case LiveSourceEnd::duration: return "duration reached";
    case LiveSourceEnd::idle: return "idle_exit: no packets";
    case LiveSourceEnd::receiver_failed: return "the receiver failed";
    case LiveSourceEnd::closed: return "closed";
  }
  return "unknown";
}

class LiveSource {
 public:
  /// Connects and starts receiving; live::ConnectionError when the LiDAR
  /// does not answer within `o.connection.wait` or a port cannot be bound.
  explicit LiveSource(const LiveSourceOptions& o) : options_(o) {
    if (o.connection.lidars.size() > 1) throw std::invalid_argument("lidar: one LiDAR per live source");
    connection_ = std::make_unique<live::LivoxConnection>(o.connection);
    connection_->start();
    stream_ = std::make_unique<live::LivoxStream>(
        o.connection.source.protocol == live::LivoxProtocol::sdk2 ? live::sdk2_packet_format() : live::sdk1_packet_format(),
        live::LivoxStream::Options{o.reorder_packets, 1'000'000'000});
    start_ = last_datagram_ = std::chrono::steady_clock::now();
  }

  ~LiveSource() { close(); }
  LiveSource(const LiveSource&) = delete;
  LiveSource& operator=(const LiveSource&) = delete;

  /// Appends the returns released until `deadline` to `out` (stream order,
  /// host clock). Returns as soon as some came, when the deadline passes or
  /// when the stream ends (what the reorder window held comes first).
  /// Polls the queue every 200 us while it is empty.
  void pull(std::vector<live::LivoxReturn>& out, std::chrono::steady_clock::time_point deadline) {
    const std::size_t before = out.size();
    for (;;) {
      if (end_ != LiveSourceEnd::running) return;
      auto now = std::chrono::steady_clock::now();
      // The duration ends the stream even under load (the queue never
      // empties when the caller is behind).
      if (options_.duration.count() > 0 && now - start_ >= options_.duration) {
        finish(LiveSourceEnd::duration, out);
        return;
      }
      bool any = false;
      for (int burst = 0; burst < 256; ++burst) {
        live::Datagram* d = connection_->receiver().queue(0).front();
        if (d == nullptr) break;
        stream_->consume(*d, out, imu_, arrivals_);
        connection_->receiver().queue(0).pop();
        any = true;
      }
      imu_.clear();
      arrivals_.clear();
      now = std::chrono::steady_clock::now();
      if (any) last_datagram_ = now;
      if (out.size() > before) {
        if (!first_) first_ = now;
        return;
      }
      if (any) continue;
      // Held packets are released after 20 ms without a datagram (the
      // reorder window must not keep a pausing stream's last points).
      if (now - last_datagram_ > std::chrono::milliseconds(20) && stream_->held() > 0) {
        stream_->flush(out, arrivals_);
        if (out.size() > before) return;
      }
      if (first_ && options_.idle_exit.count() > 0 && now - last_datagram_ >= options_.idle_exit) {
        finish(LiveSourceEnd::idle, out);
        return;
      }
      if (!connection_->receiver().error().empty()) {
        failure_ = connection_->receiver().error();
        finish(LiveSourceEnd::receiver_failed, out);
        return;
      }
      if (now >= deadline) return;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }

  /// Stops the receiver and the LiDAR (SDK1: stop sampling, disconnect).
  /// Idempotent; within one receiver poll period (20 ms).
  void close() {
    if (connection_) connection_->stop();
    if (end_ == LiveSourceEnd::running) end_ = LiveSourceEnd::closed;
  }

  LiveSourceEnd end() const { return end_; }
  /// The receiver's error when it failed (end() == receiver_failed).
  const std::string& failure() const { return failure_; }
  /// True once a first return came.
  bool started() const { return first_.has_value(); }
  /// Wall time since the connection.
  std::chrono::steady_clock::duration elapsed() const { return std::chrono::steady_clock::now() - start_; }
  /// "MODEL SERIAL" when the LiDAR was found by discovery or broadcast, else
  /// "LiDAR at ADDRESS" once it sent (empty before).
  std::string lidar_name() const { return connection_->lidar_name(0); }
  /// Where the points arrive (HOST:PORT).
  const std::string& endpoint() const { return connection_->endpoint(); }
  /// The packet counters now (docs/python.md, "Live sources").
  live::LiveCounters counters() const { return live::live_counters(connection_->receiver(), 0, *stream_); }
  const live::LivoxStream& stream() const { return *stream_; }
  const LiveSourceOptions& options() const { return options_; }

 private:
  void finish(LiveSourceEnd why, std::vector<live::LivoxReturn>& out) {
    stream_->flush(out, arrivals_);
    arrivals_.clear();
    end_ = why;
  }

  LiveSourceOptions options_;
  std::unique_ptr<live::LivoxConnection> connection_;
  std::unique_ptr<live::LivoxStream> stream_;
  std::string failure_;
  std::chrono::steady_clock::time_point start_, last_datagram_;
  std::optional<std::chrono::steady_clock::time_point> first_;
  LiveSourceEnd end_ = LiveSourceEnd::running;
  std::vector<live::LivoxImuSample> imu_;  // not used by the module: dropped each pull
  std::vector<live::PacketArrival> arrivals_;
};

}  // namespace streamclust::python
