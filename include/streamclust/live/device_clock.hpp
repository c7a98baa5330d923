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
/// moves it by years) starts a new epoch: when a packet's drift (mapped time
/// minus arrival) differs from the previous packet's by more than
/// `jump_threshold_ns`, or the sync type changes, the offset is fixed again
/// at that packet. A jump is a step between two packets, never the slow sum
/// of a clock that runs at another rate than the host's (a crystal's ppm, or
/// a replay at another speed): such a clock stays in one epoch and its
/// mapped times drift from the host's. A new epoch never maps a time before
/// the last one mapped (the stream stays ordered), so the clusterer sees a
/// continuous stream, never a flood of backwards times.
/// A packet sent before a jump and reordered after it (arriving within
/// `kStragglerWindowNs` of the epoch's first packet) fits the previous epoch,
/// not the current one: it starts no epoch and is a `straggler`. Later, a
/// clock that steps back to the previous epoch's time starts a new epoch.
///
/// Not thread-safe: one per device, on the thread that decodes its packets.

#include <streamclust/live/livox_returns.hpp>

#include <cstdint>
#include <cstdlib>
#include <limits>

namespace streamclust::live {

class DeviceClock {
 public:
  /// How long after an epoch began a packet of the previous epoch is a
  /// straggler [ns]: 20 ms, far above reordering on a link (the reorder
  /// window holds 4 ms of a Mid-360), far below a clock's glitch and return.
  static constexpr std::int64_t kStragglerWindowNs = 20'000'000;

  /// A mapped time this far from its packet's arrival starts a new epoch
  /// (default 1 s: far above network latency and a packet's span, far
  /// below a reboot's jump or a PTP step).
  explicit DeviceClock(std::int64_t jump_threshold_ns = 1'000'000'000) : jump_threshold_ns_(jump_threshold_ns) {}

  /// Observes a packet whose first point has device time `device_ns`,
  /// received at host time `arrival_ns`, with time sync `sync`. Returns true
  /// when this packet starts a new epoch (always for the first packet).
  bool observe(std::uint64_t device_ns, std::int64_t arrival_ns, LivoxTimeSync sync) noexcept {
    const bool first = epochs_ == 0;
    straggler_ = false;
    if (!first && sync == sync_ && fits(offset_ns_, last_drift_ns_, device_ns, arrival_ns)) {
      last_drift_ns_ = difference(predict(device_ns), arrival_ns);
      return false;
    }
    if (epochs_ > 1 && sync == previous_sync_ && difference(arrival_ns, epoch_arrival_ns_) <= kStragglerWindowNs &&
        fits(previous_offset_ns_, previous_drift_ns_, device_ns, arrival_ns)) {
      straggler_ = true;  // the previous epoch's: not a new one
      return false;
    }
    // New epoch: fix the offset here, no earlier than the last mapped time.
    previous_offset_ns_ = offset_ns_;
    previous_drift_ns_ = last_drift_ns_;
    previous_sync_ = sync_;
    offset_ns_ = difference(arrival_ns, static_cast<std::int64_t>(device_ns));
    if (!first && predict(device_ns) <= last_mapped_ns_)
      offset_ns_ = difference(last_mapped_ns_, static_cast<std::int64_t>(device_ns - 1));
    sync_ = sync;
    epoch_arrival_ns_ = arrival_ns;
    last_drift_ns_ = difference(predict(device_ns), arrival_ns);  // 0 unless held after the last mapped time
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

  /// True when the packet last observed fits the previous epoch and not
  /// the current one (sent before the jump, reordered after it): the caller
  /// drops it as late (its time belongs before what the epoch began after).
  bool straggler() const noexcept { return straggler_; }

  /// Epochs so far (1 after the first packet).
  std::uint32_t epochs() const noexcept { return epochs_; }
  /// The current epoch's offset [ns]: host time - device time.
  std::int64_t offset_ns() const noexcept { return offset_ns_; }
  /// The current epoch's time sync.
  LivoxTimeSync sync() const noexcept { return sync_; }
  /// Mapped time minus arrival of the last packet observed [ns]: follows
  /// the drift between the two clocks and the network's delay.
  std::int64_t last_drift_ns() const noexcept { return last_drift_ns_; }

 private:
  // Two's-complement arithmetic without signed overflow: device times are
  // whatever a packet says.
  std::int64_t predict(std::uint64_t device_ns, std::int64_t offset_ns) const noexcept {
    return static_cast<std::int64_t>(device_ns + static_cast<std::uint64_t>(offset_ns));
  }
  std::int64_t predict(std::uint64_t device_ns) const noexcept { return predict(device_ns, offset_ns_); }
  // The drift of device time mapped by `offset_ns` is within the threshold
  // of `reference_drift_ns` (the epoch's previous packet's).
  bool fits(std::int64_t offset_ns, std::int64_t reference_drift_ns, std::uint64_t device_ns,
            std::int64_t arrival_ns) const noexcept {
    const std::int64_t step = difference(difference(predict(device_ns, offset_ns), arrival_ns), reference_drift_ns);
    return step <= jump_threshold_ns_ && step >= -jump_threshold_ns_;
  }
  static std::int64_t difference(std::int64_t a, std::int64_t b) noexcept {
    return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) - static_cast<std::uint64_t>(b));
  }

  std::int64_t jump_threshold_ns_;
  std::int64_t offset_ns_ = 0, previous_offset_ns_ = 0;
  std::int64_t last_mapped_ns_ = std::numeric_limits<std::int64_t>::min();
  std::int64_t last_drift_ns_ = 0, previous_drift_ns_ = 0;  // mapped time - arrival of an epoch's last packet [ns]
  std::int64_t epoch_arrival_ns_ = 0;  // arrival of the current epoch's first packet [ns]
  LivoxTimeSync sync_ = LivoxTimeSync::none, previous_sync_ = LivoxTimeSync::none;
  bool straggler_ = false;
  std::uint32_t epochs_ = 0;
};

}  // namespace streamclust::live
