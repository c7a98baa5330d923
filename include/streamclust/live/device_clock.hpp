// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The LiDAR's clock mapped to the host's. The LiDAR's clock gives the
/// stream its times (its per-point spacing is exact); one offset, fixed at
/// the first packet (host arrival time minus device time), places them on
/// the host's clock (ns since the Unix epoch), so several LiDARs and the
/// host's own logs share one time line. The offset includes that packet's
/// network latency (tens of microseconds on a direct link).
///
/// A clock jump (a reboot restarts the clock at 0; acquiring PTP or GPS
/// moves it by years) starts a new epoch: when a packet's mapped time and
/// its arrival differ by more than `jump_threshold_ns`, or the sync type
/// changes, the offset is fixed again at that packet. A new epoch never maps
/// a time before the last one mapped (the stream stays ordered), so the
/// clusterer sees a continuous stream, never a flood of backwards times.
///
/// Not thread-safe: one per device, on the thread that decodes its packets.

#include <streamclust/live/livox_returns.hpp>

#include <cstdint>
#include <cstdlib>
#include <limits>

namespace streamclust::live {

class DeviceClock {
 public:
  /// A mapped time this far from its packet's arrival starts a new epoch
  /// (default 1 s: far above network latency and a packet's span, far
  /// below a reboot's jump or a PTP step).
  explicit DeviceClock(std::int64_t jump_threshold_ns = 1'000'000'000) : jump_threshold_ns_(jump_threshold_ns) {}

  /// Observes a packet whose first point has device time `device_ns`,
  /// received at host time `arrival_ns`, with time sync `sync`. Returns true
  /// when this packet starts a new epoch (always for the first packet).
  bool observe(std::uint64_t device_ns, std::int64_t arrival_ns, LivoxTimeSync sync) noexcept {
    const bool first = epochs_ == 0;
    if (!first && sync == sync_) {
      const std::int64_t drift = difference(predict(device_ns), arrival_ns);
      if (drift <= jump_threshold_ns_ && drift >= -jump_threshold_ns_) {
        last_drift_ns_ = drift;
        return false;
      }
    }
    // New epoch: fix the offset here, no earlier than the last mapped time.
    offset_ns_ = difference(arrival_ns, static_cast<std::int64_t>(device_ns));
    if (!first && predict(device_ns) <= last_mapped_ns_)
      offset_ns_ = difference(last_mapped_ns_, static_cast<std::int64_t>(device_ns - 1));
    sync_ = sync;
    last_drift_ns_ = difference(predict(device_ns), arrival_ns);
    ++epochs_;
    return true;
  }

  /// Host time [ns since the Unix epoch] of device time `device_ns` in the
  /// current epoch; remembers the latest for the next epoch's floor.
  std::int64_t map(std::uint64_t device_ns) noexcept {
    const std::int64_t t = predict(device_ns);
    if (t > last_mapped_ns_) last_mapped_ns_ = t;
    return t;
  }

  /// Epochs so far (1 after the first packet).
  std::uint32_t epochs() const noexcept { return epochs_; }
  /// The current epoch's offset [ns]: host time - device time.
  std::int64_t offset_ns() const noexcept { return offset_ns_; }
  /// The current epoch's time sync.
  LivoxTimeSync sync() const noexcept { return sync_; }
  /// Mapped time minus arrival of the last packet observed [ns]: grows with
  /// the drift between the two clocks and with queueing delay.
  std::int64_t last_drift_ns() const noexcept { return last_drift_ns_; }

 private:
  // Two's-complement arithmetic without signed overflow: device times are
  // whatever a packet says.
  std::int64_t predict(std::uint64_t device_ns) const noexcept {
    return static_cast<std::int64_t>(device_ns + static_cast<std::uint64_t>(offset_ns_));
  }
  static std::int64_t difference(std::int64_t a, std::int64_t b) noexcept {
    return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) - static_cast<std::uint64_t>(b));
  }

  std::int64_t jump_threshold_ns_;
  std::int64_t offset_ns_ = 0;
  std::int64_t last_mapped_ns_ = std::numeric_limits<std::int64_t>::min();
  std::int64_t last_drift_ns_ = 0;
  LivoxTimeSync sync_ = LivoxTimeSync::none;
  std::uint32_t epochs_ = 0;
};

}  // namespace streamclust::live
