// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// One LiDAR's datagrams turned into its ordered stream of returns: decode
/// (either protocol), map the LiDAR's clock to the host's (DeviceClock: an
/// offset per epoch), undo reordering and drop duplicates (ReorderWindow),
/// and count every packet that could not be used, by reason.
///
/// The engine thread runs it: the receiver thread only hands datagrams over.
/// Returns leave with `time_ns` on the host's clock [ns since the Unix
/// epoch]; IMU samples likewise. No allocation once the reorder slots' and
/// the caller's vectors are warm. Not thread-safe: one per LiDAR.

#include <streamclust/live/device_clock.hpp>
#include <streamclust/live/livox_returns.hpp>
#include <streamclust/live/packet_order.hpp>
#include <streamclust/live/udp_socket.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace streamclust::live {

/// How a protocol's data packets are read: the decoder, and the expected
/// spacing of consecutive point packets for loss counting where packets
/// carry no counter (0: unknown, or counted by the packet counter).
struct LivoxPacketFormat {
  std::function<LivoxPacketSummary(const std::uint8_t*, std::size_t, LivoxPacketContents&)> decode;
  std::function<std::int64_t(const LivoxPacketSummary&)> packet_period_ns = [](const LivoxPacketSummary&) {
    return std::int64_t{0};
  };
};

/// What a stream has used and refused so far.
struct LivoxStreamCounters {
  std::uint64_t point_packets = 0;   ///< decoded point packets (before reordering)
  std::uint64_t imu_packets = 0;     ///< decoded IMU packets
  std::uint64_t returns = 0;         ///< returns released to the caller
  std::uint64_t empty_slots = 0;     ///< slots without a return (no echo, out of the FOV)
  std::uint64_t imu_before_clock = 0;  ///< IMU samples before the first point packet fixed the clock: dropped
  /// Datagrams that are no packet of the protocol, by LivoxPacketStatus
  /// (truncated .. bad_time; the first two entries stay 0).
  std::array<std::uint64_t, 8> malformed{};
  std::uint32_t epochs = 0;          ///< clock epochs (1 after the first packet)
  std::uint8_t data_type = 0;        ///< the data_type byte of the last point packet decoded

  std::uint64_t malformed_total() const noexcept {
    std::uint64_t n = 0;
    for (const std::uint64_t m : malformed) n += m;
    return n;
  }
};

/// A released packet's arrival, for latency measurements.
struct PacketArrival {
  std::int64_t last_time_ns = 0;       ///< stream time of its last return [ns]
  std::int64_t arrival_steady_ns = 0;  ///< host steady clock when it arrived [ns]
};

class LivoxStream {
 public:
  struct Options {
    std::size_t reorder_depth = 8;                 ///< packets held to undo reordering (about 4 ms of a Mid-360)
    std::int64_t clock_jump_ns = 1'000'000'000;    ///< DeviceClock's epoch threshold
  };

  LivoxStream(LivoxPacketFormat format, Options options)
      : format_(std::move(format)), clock_(options.clock_jump_ns), order_(options.reorder_depth) {}

  /// Consumes one datagram. Returns of the packets it releases (in time
  /// order) are appended to `returns`, their arrivals to `arrivals`; an IMU
  /// sample to `imu`.
  void consume(const Datagram& d, std::vector<LivoxReturn>& returns, std::vector<LivoxImuSample>& imu,
               std::vector<PacketArrival>& arrivals) {
    Held& slot = order_.next_slot();
    slot.contents.returns.clear();
    const LivoxPacketSummary s = format_.decode(d.bytes.data(), d.size, slot.contents);
    if (s.status == LivoxPacketStatus::imu) {
      ++counters_.imu_packets;
      if (clock_.epochs() == 0) {
        ++counters_.imu_before_clock;
        return;
      }
      LivoxImuSample sample = slot.contents.imu;
      sample.time_ns = static_cast<std::uint64_t>(clock_.map(sample.time_ns));
      imu.push_back(sample);
      return;
    }
    if (s.status != LivoxPacketStatus::points) {
      ++counters_.malformed[static_cast<std::size_t>(s.status) & 7u];
      return;
    }
    ++counters_.point_packets;
    counters_.data_type = s.data_type;
    counters_.empty_slots += s.empty_slots;
    if (clock_.observe(s.first_time_ns, d.arrival_ns, s.sync)) {
      // A new epoch: what the old one holds goes first, in its own order.
      if (clock_.epochs() > 1) {
        order_.flush([&](const Held& h) { release(h, returns, arrivals); });
        order_.restart();
      }
      counters_.epochs = clock_.epochs();
    } else if (clock_.straggler()) {  // the previous epoch's, which was flushed: late
      order_.count_late();
      return;
    }
    for (LivoxReturn& r : slot.contents.returns) r.time_ns = static_cast<std::uint64_t>(clock_.map(r.time_ns));
    slot.arrival_steady_ns = d.arrival_steady_ns;
    slot.last_time_ns = clock_.map(s.last_time_ns);
    const PacketKey key{clock_.map(s.first_time_ns), s.has_counter, s.counter, format_.packet_period_ns(s)};
    order_.commit(key, [&](const Held& h) { release(h, returns, arrivals); });
  }

  /// Releases every held packet (the stream went idle or ends).
  void flush(std::vector<LivoxReturn>& returns, std::vector<PacketArrival>& arrivals) {
    order_.flush([&](const Held& h) { release(h, returns, arrivals); });
  }

  const LivoxStreamCounters& counters() const noexcept { return counters_; }
  const OrderCounters& order() const noexcept { return order_.counters(); }
  const DeviceClock& clock() const noexcept { return clock_; }
  /// Packets held for reordering now.
  std::size_t held() const noexcept { return order_.held(); }

 private:
  struct Held {
    LivoxPacketContents contents;
    std::int64_t arrival_steady_ns = 0;
    std::int64_t last_time_ns = 0;
  };

  void release(const Held& h, std::vector<LivoxReturn>& returns, std::vector<PacketArrival>& arrivals) {
    returns.insert(returns.end(), h.contents.returns.begin(), h.contents.returns.end());
    counters_.returns += h.contents.returns.size();
    arrivals.push_back(PacketArrival{h.last_time_ns, h.arrival_steady_ns});
  }

  LivoxPacketFormat format_;
  DeviceClock clock_;
  ReorderWindow<Held> order_;
  LivoxStreamCounters counters_;
};

}  // namespace streamclust::live
