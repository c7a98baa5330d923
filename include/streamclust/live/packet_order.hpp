// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Packets back in the LiDAR's order. UDP may reorder and duplicate
/// datagrams; the clusterer wants points in time order. A reorder window
/// holds the last `depth` packets sorted by the mapped time of their first
/// point and releases the oldest when a new one arrives beyond the depth;
/// a packet that arrives after a later one was released is late and
/// dropped, one seen before is a duplicate and dropped. Lost packets are
/// counted at release: from the packet counter where the protocol has one
/// (SDK2 udp_cnt, wrapping at 65535: lost = (counter - previous - 1) mod
/// 2^16), else from the time gap over the packet period (SDK1).
///
/// Packets are slots of a pool allocated once (`depth` + 1 of them): the
/// caller fills `next_slot()` and `commit`s it, with no allocation once each
/// slot's buffers are warm. O(depth) per packet.
///
/// Not thread-safe: one per device stream.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace streamclust::live {

/// What the reorder window dropped and inferred.
struct OrderCounters {
  std::uint64_t released = 0;       ///< packets handed on in order
  std::uint64_t lost = 0;           ///< packets missing between released ones
  std::uint64_t late = 0;           ///< arrived after a later packet was released: dropped
  std::uint64_t duplicates = 0;     ///< same counter and time as one seen: dropped
  std::uint64_t counter_jumps = 0;  ///< counter discontinuities too large to be loss (not counted as lost)
};

/// The ordering key of a packet.
struct PacketKey {
  std::int64_t first_ns = 0;     ///< mapped time of the first point [ns]
  bool has_counter = false;
  std::uint16_t counter = 0;
  std::int64_t period_ns = 0;    ///< expected spacing of consecutive packets [ns] (loss without a counter); 0: unknown
};

/// A gap of more packets than this on the counter is a discontinuity (a
/// counter reset without a clock jump), not loss: 2^10 packets are about
/// 0.5 s of a Mid-360.
inline constexpr std::uint16_t kMaxCountedLoss = 1024;

template <class Packet>
class ReorderWindow {
 public:
  /// A window of `depth` packets (0: release each packet at once).
  explicit ReorderWindow(std::size_t depth) : depth_(depth), pool_(depth + 1) {
    free_.reserve(depth + 1);
    held_.reserve(depth + 1);
    for (std::size_t i = 0; i <= depth; ++i) free_.push_back(i);
  }

  std::size_t depth() const noexcept { return depth_; }
  std::size_t held() const noexcept { return held_.size(); }

  /// The slot to fill with the next packet: the same until `commit`, also
  /// across a `flush` (a new epoch flushes while the packet is being read).
  Packet& next_slot() noexcept { return pool_[free_.back()].packet; }

  /// Adds the filled slot with `key`; then releases packets beyond the
  /// depth, oldest first, calling `release(const Packet&)` for each in order.
  template <class Release>
  void commit(const PacketKey& key, Release&& release) {
    const std::size_t slot = free_.back();
    free_.pop_back();
    pool_[slot].key = key;
    // Insertion keeps held_ sorted by time, arrival order among equal times.
    auto at = std::upper_bound(held_.begin(), held_.end(), key.first_ns, [this](std::int64_t t, std::size_t s) {
      return t < pool_[s].key.first_ns;
    });
    held_.insert(at, slot);
    while (held_.size() > depth_) release_oldest(release);
  }

  /// Releases every held packet in order (at the end of an epoch or when
  /// the stream goes idle).
  template <class Release>
  void flush(Release&& release) {
    while (!held_.empty()) release_oldest(release);
  }

  /// Forgets the last released packet (a new clock epoch: times and
  /// counters start over). Call after `flush`.
  void restart() noexcept {
    have_last_ = false;
    recent_count_ = 0;
  }

  /// Counts a packet the caller drops as late before committing it (one
  /// of a clock epoch already flushed).
  void count_late() noexcept { ++counters_.late; }

  const OrderCounters& counters() const noexcept { return counters_; }

 private:
  struct Slot {
    Packet packet{};
    PacketKey key;
  };

  template <class Release>
  void release_oldest(Release& release) {
    const std::size_t slot = held_.front();
    held_.erase(held_.begin());
    free_.insert(free_.begin(), slot);  // behind the slot next_slot() handed out
    const PacketKey& k = pool_[slot].key;
    if (have_last_ && k.first_ns <= last_.first_ns) {
      if (seen(k)) {
        ++counters_.duplicates;
      } else {
        ++counters_.late;
      }
      return;
    }
    if (have_last_) count_loss(k);
    last_ = k;
    have_last_ = true;
    remember(k);
    ++counters_.released;
    release(static_cast<const Packet&>(pool_[slot].packet));
  }

  void count_loss(const PacketKey& k) noexcept {
    if (k.has_counter && last_.has_counter) {
      const auto gap = static_cast<std::uint16_t>(k.counter - last_.counter - 1u);
      if (gap < kMaxCountedLoss) {
        counters_.lost += gap;
      } else {
        ++counters_.counter_jumps;
      }
    } else if (k.period_ns > 0) {
      // Packets fit in the gap beyond the one expected; half a period of
      // slack for jitter in the stamps.
      const std::int64_t gap = k.first_ns - last_.first_ns;
      const std::int64_t missing = (gap + k.period_ns / 2) / k.period_ns - 1;
      if (missing > 0) counters_.lost += static_cast<std::uint64_t>(missing);
    }
  }

  // The last released keys, to tell a duplicate from a late packet.
  static constexpr std::size_t kRecent = 64;
  bool seen(const PacketKey& k) const noexcept {
    const std::size_t n = std::min(recent_count_, kRecent);
    for (std::size_t i = 0; i < n; ++i) {
      const PacketKey& r = recent_[i];
      if (r.first_ns == k.first_ns && r.has_counter == k.has_counter && r.counter == k.counter) return true;
    }
    return false;
  }
  void remember(const PacketKey& k) noexcept { recent_[recent_count_++ % kRecent] = k; }

  std::size_t depth_;
  std::vector<Slot> pool_;
  std::vector<std::size_t> free_;
  std::vector<std::size_t> held_;  // sorted by key.first_ns
  PacketKey last_;
  bool have_last_ = false;
  std::array<PacketKey, kRecent> recent_{};
  std::size_t recent_count_ = 0;
  OrderCounters counters_;
};

}  // namespace streamclust::live
