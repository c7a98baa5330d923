// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Livox returns as the messages the Livox ROS 2 driver publishes
/// (livox_ros_driver2/msg/CustomMsg, CDR): the header stamp and `timebase`
/// are the first return's time, each point's `offset_time` the nanoseconds
/// after it. Used by `live --record` and `replay --to ros2://`.

#include <streamclust/io/cdr_writer.hpp>
#include <streamclust/live/livox_returns.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace streamclust::cli {

/// Writes returns[from, to) (times in order, within 4.29 s of the first) as
/// one CustomMsg in `frame_id`. O(returns).
inline void write_custom_msg(io::CdrWriter& w, const std::string& frame_id,
                             const std::vector<live::LivoxReturn>& returns, std::size_t from, std::size_t to) {
  const std::uint64_t base = from < to ? returns[from].time_ns : 0;
  w.clear();
  w.i32(static_cast<std::int32_t>(base / 1'000'000'000u));  // header.stamp
  w.u32(static_cast<std::uint32_t>(base % 1'000'000'000u));
  w.string(frame_id);
  w.u64(base);                                        // timebase
  w.u32(static_cast<std::uint32_t>(to - from));       // point_num
  w.u8(0);                                            // lidar_id
  for (int i = 0; i < 3; ++i) w.u8(0);                // rsvd
  w.count(to - from);
  for (std::size_t i = from; i < to; ++i) {
    const live::LivoxReturn& r = returns[i];
    w.u32(static_cast<std::uint32_t>(r.time_ns - base));
    w.f32(r.x);
    w.f32(r.y);
    w.f32(r.z);
    w.u8(r.reflectivity);
    w.u8(r.tag);
    w.u8(0);  // line: no laser lines on a Risley-prism sensor
  }
}

}  // namespace streamclust::cli
