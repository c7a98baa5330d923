// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// LiveCounters: one LiDAR's packet counters from the receiver and the
/// stream, taken together, with their names as the tool's `--report` and
/// the Python module's `counters` spell them (docs/live.md, "Threads, queues and what is counted").
///
/// Thread safety: `live_counters` reads the receiver's atomics (any thread)
/// and the stream's counters (the thread that consumes the stream only).

#include <streamclust/live/livox_receiver.hpp>
#include <streamclust/live/livox_stream.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>

namespace streamclust::live {

struct LiveCounters {
  std::uint64_t datagrams = 0;      ///< from this LiDAR
  std::uint64_t bytes = 0;          ///< their payload bytes
  std::uint64_t point_packets = 0;  ///< decoded point packets
  std::uint64_t imu_packets = 0;    ///< decoded IMU packets
  std::uint64_t returns = 0;        ///< returns released to the engine
  std::uint64_t empty_slots = 0;    ///< slots without a return
  std::uint64_t lost = 0;           ///< packets missing (counter or time gaps)
  std::uint64_t late = 0;           ///< came after the reorder window: dropped
  std::uint64_t duplicates = 0;     ///< seen before: dropped
  std::uint64_t counter_jumps = 0;  ///< counter discontinuities too large to be loss
  std::uint64_t malformed = 0;      ///< no packet of the protocol: dropped
  std::uint64_t foreign = 0;        ///< from other addresses on the port (every LiDAR of the receiver)
  std::uint64_t oversize = 0;       ///< longer than any Livox packet (every LiDAR of the receiver)
  std::uint64_t queue_drops = 0;    ///< the engine fell behind: whole packets dropped
  std::optional<std::uint64_t> kernel_drops;  ///< the OS's drops for want of buffer, where it reports them
};

/// The counters of LiDAR `device` of `receiver`, whose packets `stream`
/// consumes. O(1).
inline LiveCounters live_counters(const LivoxReceiver& receiver, std::size_t device, const LivoxStream& stream) {
  const ReceiverStats rs = receiver.stats();
  const LivoxStreamCounters& sc = stream.counters();
  const OrderCounters& oc = stream.order();
  LiveCounters c;
  c.datagrams = receiver.datagrams(device);
  c.bytes = receiver.bytes(device);
  c.point_packets = sc.point_packets;
  c.imu_packets = sc.imu_packets;
  c.returns = sc.returns;
  c.empty_slots = sc.empty_slots;
  c.lost = oc.lost;
  c.late = oc.late;
  c.duplicates = oc.duplicates;
  c.counter_jumps = oc.counter_jumps;
  c.malformed = sc.malformed_total();
  c.foreign = rs.foreign;
  c.oversize = rs.oversize;
  c.queue_drops = receiver.queue_drops(device);
  if (rs.kernel_drops_known) c.kernel_drops = rs.kernel_drops;
  return c;
}

/// Calls `f(name, value)` for every counter that `c` has (kernel_drops only
/// where the OS reports it), in the report's order.
template <class F>
void for_each_counter(const LiveCounters& c, F&& f) {
  f("datagrams", c.datagrams);
  f("bytes", c.bytes);
  f("point_packets", c.point_packets);
  f("imu_packets", c.imu_packets);
  f("returns", c.returns);
  f("empty_slots", c.empty_slots);
  f("lost", c.lost);
  f("late", c.late);
  f("duplicates", c.duplicates);
  f("counter_jumps", c.counter_jumps);
  f("malformed", c.malformed);
  f("foreign", c.foreign);
  f("oversize", c.oversize);
  f("queue_drops", c.queue_drops);
  if (c.kernel_drops) f("kernel_drops", *c.kernel_drops);
}

}  // namespace streamclust::live
