// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The engine side of `streamclust live` and `streamclust ros2`: a source's
/// points, received by another thread and queued, drained and ordered by a
/// `LiveInput` (a LiDAR's packets, a topic's messages), handed to the
/// clusterer as point records through `LiveReader`, an io::PointReader, so
/// the driver of `cluster` runs a live source with all its outputs. The
/// feed keeps what it has handed out while the run is being set up (the
/// first window, read once for the ground estimate and then again by the
/// driver), and ends the stream on a stop request (SIGINT, SIGTERM), after
/// --duration or after --idle-exit seconds without input.
///
/// Not thread-safe: the engine thread owns it; the receiving thread only
/// fills the input's queue.

#include "cli/live_recorder.hpp"

#include <streamclust/io/point_reader.hpp>
#include <streamclust/io/ros/point_messages.hpp>
#include <streamclust/live/livox_receiver.hpp>
#include <streamclust/live/livox_stream.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace streamclust::cli {

/// Why a live stream ended.
enum class LiveEnd { running, stop_requested, duration, idle, receiver_failed };

inline const char* describe(LiveEnd e) {
  switch (e) {
    case LiveEnd::running: return "running";
    case LiveEnd::stop_requested: return "stopped by a signal";
    case LiveEnd::duration: return "--duration reached";
    case LiveEnd::idle: return "--idle-exit: no packets";
    case LiveEnd::receiver_failed: return "the receiver failed";
  }
  return "unknown";
}

/// A point is a point of a message: metres, intensity, absolute time [ns].
using LivePoint = io::ros::TimedPoint;

/// What a feed drains: the queue another thread fills, decoded into
/// points in stream order. Engine thread only.
class LiveInput {
 public:
  virtual ~LiveInput() = default;
  /// Consumes up to a burst of what has arrived, appending its points, IMU
  /// samples and arrivals; false when nothing had arrived.
  virtual bool poll(std::vector<LivePoint>& points, std::vector<live::LivoxImuSample>& imu,
                    std::vector<live::PacketArrival>& arrivals) = 0;
  /// Points held back to undo reordering; `flush` releases them.
  virtual std::size_t held() const { return 0; }
  virtual void flush(std::vector<LivePoint>&, std::vector<live::PacketArrival>&) {}
  /// The receiving side's failure, empty while it works.
  virtual std::string error() const = 0;
  /// Items (packets, messages) waiting in the queue.
  virtual std::size_t queue_depth() const = 0;
};

/// A Livox LiDAR's packets: one receiver queue, decoded and ordered by
/// its LivoxStream, recorded raw (--record) when a recorder is given.
class LivoxInput final : public LiveInput {
 public:
  LivoxInput(live::LivoxReceiver& receiver, std::size_t device, live::LivoxStream& stream, LiveRecorder* recorder)
      : receiver_(receiver), device_(device), stream_(stream), recorder_(recorder) {}

  bool poll(std::vector<LivePoint>& points, std::vector<live::LivoxImuSample>& imu,
            std::vector<live::PacketArrival>& arrivals) override {
    bool any = false;
    for (int burst = 0; burst < 256; ++burst) {
      live::Datagram* d = receiver_.queue(device_).front();
      if (d == nullptr) break;
      const std::size_t imu_before = imu.size();
      returns_.clear();
      stream_.consume(*d, returns_, imu, arrivals);
      receiver_.queue(device_).pop();
      take(points, imu, imu_before);
      any = true;
    }
    return any;
  }
  std::size_t held() const override { return stream_.held(); }
  void flush(std::vector<LivePoint>& points, std::vector<live::PacketArrival>& arrivals) override {
    returns_.clear();
    stream_.flush(returns_, arrivals);
    std::vector<live::LivoxImuSample> none;
    take(points, none, 0);
  }
  std::string error() const override { return receiver_.error(); }
  std::size_t queue_depth() const override { return receiver_.queue(device_).size(); }

 private:
  void take(std::vector<LivePoint>& points, const std::vector<live::LivoxImuSample>& imu, std::size_t imu_from) {
    if (recorder_) {
      recorder_->add_returns(returns_);
      for (std::size_t i = imu_from; i < imu.size(); ++i) recorder_->add_imu(imu[i]);
    }
    for (const live::LivoxReturn& r : returns_) {
      LivePoint p;
      p.x = r.x;
      p.y = r.y;
      p.z = r.z;
      p.intensity = r.reflectivity;
      p.t_ns = r.time_ns;
      points.push_back(p);
    }
  }

  live::LivoxReceiver& receiver_;
  std::size_t device_;
  live::LivoxStream& stream_;
  LiveRecorder* recorder_;
  std::vector<live::LivoxReturn> returns_;
};

class LiveFeed {
 public:
  struct Limits {
    std::chrono::steady_clock::duration duration{};   ///< zero: none
    std::chrono::steady_clock::duration idle_exit{};  ///< zero: none
    /// Held packets are released after this long without a datagram (the
    /// reorder window must not keep a pausing stream's last points).
    std::chrono::steady_clock::duration idle_flush = std::chrono::milliseconds(20);
  };

  /// `stop` is polled (a signal handler sets it).
  LiveFeed(LiveInput& input, Limits limits, const std::atomic<bool>& stop)
      : input_(input), limits_(limits), stop_(stop), start_(std::chrono::steady_clock::now()), last_datagram_(start_) {}

  /// Waits for the first returns (a first packet), at most `timeout`;
  /// false when none came (or the run was stopped).
  bool wait_for_first(std::chrono::steady_clock::duration timeout) {
    const auto until = std::chrono::steady_clock::now() + timeout;
    while (history_.empty()) {
      if (!pull_more(until)) return false;
    }
    return true;
  }

  /// The device time of the first return [ns, host clock]; valid after
  /// wait_for_first returned true.
  std::uint64_t first_time_ns() const { return history_.front().t_ns; }

  /// Keeps every return handed out in a history that new readers replay
  /// from its start (while the run is set up); `false` drops it and feeds
  /// only the reader created last.
  void keep_history(bool keep) {
    keep_history_ = keep;  // off: the history shrinks as the reader passes it
  }

  /// Returns for reader position `position` (a count of returns since the
  /// stream started): appends up to `max` to `out` and advances `position`;
  /// blocks until at least one is there. 0: the stream ended.
  std::size_t read(std::uint64_t& position, std::vector<LivePoint>& out, std::size_t max) {
    for (;;) {
      if (position < history_base_) position = history_base_;  // dropped history: skip (not while setting up)
      const std::uint64_t end = history_base_ + history_.size();
      if (position < end) {
        const std::size_t at = static_cast<std::size_t>(position - history_base_);
        const std::size_t n = std::min<std::size_t>(max, history_.size() - at);
        out.insert(out.end(), history_.begin() + static_cast<std::ptrdiff_t>(at),
                   history_.begin() + static_cast<std::ptrdiff_t>(at + n));
        position += n;
        if (!keep_history_) {
          // The driver's reader is the only one left: forget what it has read.
          const std::size_t drop = static_cast<std::size_t>(position - history_base_);
          history_.erase(history_.begin(), history_.begin() + static_cast<std::ptrdiff_t>(drop));
          history_base_ = position;
        }
        return n;
      }
      if (!pull_more(std::chrono::steady_clock::time_point::max())) return 0;
    }
  }

  /// IMU samples received so far that no one has taken (stream clock).
  std::vector<live::LivoxImuSample> take_imu() {
    std::vector<live::LivoxImuSample> taken;
    taken.swap(imu_);
    return taken;
  }

  /// Arrivals of the packets whose returns were handed out, oldest first;
  /// the caller pops what it has accounted for.
  std::deque<live::PacketArrival>& arrivals() { return arrivals_; }

  LiveEnd end() const { return end_; }
  /// When the driver, set up, first waited for input (the backlog of the
  /// setup cleared): the start of the steady state. Nothing before.
  std::optional<std::chrono::steady_clock::time_point> caught_up() const { return caught_up_; }
  std::size_t queue_depth() { return input_.queue_depth(); }
  /// Wall time since the feed started.
  std::chrono::steady_clock::duration elapsed() const { return std::chrono::steady_clock::now() - start_; }

 private:
  // Drains the queue into the history until it grows, the deadline passes
  // (false) or the stream ends (false, end_ set).
  bool pull_more(std::chrono::steady_clock::time_point deadline) {
    const std::size_t before = history_.size();
    for (;;) {
      if (end_ != LiveEnd::running) return false;
      auto now = std::chrono::steady_clock::now();
      // A stop request or the duration ends the stream even under load (the
      // queue never empties when the engine is behind).
      if (stop_.load(std::memory_order_relaxed)) {
        finish(LiveEnd::stop_requested);
      } else if (limits_.duration.count() > 0 && now - start_ >= limits_.duration) {
        finish(LiveEnd::duration);
      }
      if (end_ != LiveEnd::running) return history_.size() > before;
      const bool any = input_.poll(scratch_, imu_scratch_, arrival_scratch_);
      take_scratch();
      now = std::chrono::steady_clock::now();
      if (any) {
        last_datagram_ = now;
        received_ = true;
      }
      if (history_.size() > before) return true;
      if (any) continue;
      if (now - last_datagram_ > limits_.idle_flush && input_.held() > 0) {
        input_.flush(scratch_, arrival_scratch_);
        take_scratch();
        if (history_.size() > before) return true;
      }
      // Idle only counts once the stream has started (before that, --wait).
      if (received_ && limits_.idle_exit.count() > 0 && now - last_datagram_ >= limits_.idle_exit) {
        finish(LiveEnd::idle);
      } else if (!input_.error().empty()) {
        finish(LiveEnd::receiver_failed);
      }
      if (end_ != LiveEnd::running) return history_.size() > before;
      if (now >= deadline) return false;
      // The driver waits for input: the run has caught up with the stream.
      if (!keep_history_ && !caught_up_) caught_up_ = now;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }

  // The stream ends: what the reorder window holds is released first.
  void finish(LiveEnd why) {
    input_.flush(scratch_, arrival_scratch_);
    take_scratch();
    end_ = why;
  }

  void take_scratch() {
    history_.insert(history_.end(), scratch_.begin(), scratch_.end());
    imu_.insert(imu_.end(), imu_scratch_.begin(), imu_scratch_.end());
    if (imu_.size() > kMaxImuKept) imu_.erase(imu_.begin(), imu_.end() - static_cast<std::ptrdiff_t>(kMaxImuKept));
    arrivals_.insert(arrivals_.end(), arrival_scratch_.begin(), arrival_scratch_.end());
    if (arrivals_.size() > kMaxArrivalsKept)
      arrivals_.erase(arrivals_.begin(), arrivals_.end() - static_cast<std::ptrdiff_t>(kMaxArrivalsKept));
    scratch_.clear();
    imu_scratch_.clear();
    arrival_scratch_.clear();
  }

  // Bounds of what waits for a consumer: 10 s of a 200 Hz IMU, 10 s of
  // point packets.
  static constexpr std::size_t kMaxImuKept = 2000;
  static constexpr std::size_t kMaxArrivalsKept = 20000;

  LiveInput& input_;
  Limits limits_;
  const std::atomic<bool>& stop_;
  std::chrono::steady_clock::time_point start_, last_datagram_;
  bool received_ = false;  // a first datagram came (idle time counts from then on)
  LiveEnd end_ = LiveEnd::running;
  bool keep_history_ = true;
  std::optional<std::chrono::steady_clock::time_point> caught_up_;
  std::deque<LivePoint> history_;
  std::uint64_t history_base_ = 0;
  std::vector<LivePoint> scratch_;
  std::vector<live::LivoxImuSample> imu_scratch_, imu_;
  std::vector<live::PacketArrival> arrival_scratch_;
  std::deque<live::PacketArrival> arrivals_;
};

/// The feed as an io::PointReader: records in nanoseconds of the host
/// clock (a LiDAR) or of the messages' stamps (a topic) from the given time
/// origin, so they equal what `cluster` reads from the same points
/// recorded (--record).
class LiveReader : public io::PointReader {
 public:
  /// `fields` and `time_field` describe the input in the report
  /// (CustomMsg's by default).
  LiveReader(LiveFeed& feed, const std::string& name, io::TimeOrigin origin,
             std::vector<std::string> fields = {"x", "y", "z", "reflectivity", "offset_time"},
             std::string time_field = "offset_time")
      : PointReader(name), feed_(feed) {
    info_.format = io::Format::mcap;  // what --record writes; the report names the live source
    info_.has_time = true;
    info_.time_field = std::move(time_field);
    info_.fields = std::move(fields);
    io::ReadOptions options;
    options.time_origin = origin;
    setup_time(options, io::TimeUnit::ns);
  }

  /// Also appends every record read to `*tap` (null: none); the owner
  /// empties it.
  void tap(std::vector<io::Record>* tap) { tap_ = tap; }

  std::size_t read(std::vector<io::Record>& out, std::size_t max_records) override {
    if (max_records == 0) return 0;
    points_.clear();
    const std::size_t first = out.size();
    const std::size_t n = feed_.read(position_, points_, max_records);
    for (const LivePoint& p : points_) {
      io::Record rec;
      rec.x = p.x;
      rec.y = p.y;
      rec.z = p.z;
      rec.intensity = p.intensity;
      rec.label = p.label;
      rec.t = next_time_unsigned(p.t_ns);
      out.push_back(rec);
    }
    if (tap_) tap_->insert(tap_->end(), out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
    return n;
  }

 private:
  LiveFeed& feed_;
  std::vector<io::Record>* tap_ = nullptr;
  std::uint64_t position_ = 0;
  std::vector<LivePoint> points_;
};

}  // namespace streamclust::cli
