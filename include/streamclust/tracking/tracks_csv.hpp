// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The tracks CSV (`cluster --tracks FILE`): one row per track per cycle,
///
///   cycle,time,track_id,cluster_id,x,y,z,vx,vy,vz,length,width,height,yaw,points,state
///
/// time as the labels file writes it (stream_time.hpp: seconds, an epoch's
/// origin shifted into the text); x..z the box centre [m], vx..vz [m/s],
/// length, width, height [m], yaw [rad], all in the world frame of the run;
/// cluster_id -1 when the track was not seen this cycle; state tentative, confirmed or
/// coasting. Numbers in their shortest round-trip text.

#include <streamclust/io/stream_time.hpp>
#include <streamclust/io/writers.hpp>
#include <streamclust/tracking/track.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace streamclust::tracking {

/// The header line of the tracks CSV, without its newline.
inline constexpr const char* kTracksCsvHeader =
    "cycle,time,track_id,cluster_id,x,y,z,vx,vy,vz,length,width,height,yaw,points,state";

/// Appends the rows of `tracks` at cycle `cycle` and stream time `time` [s]
/// to `out`. O(tracks).
inline void append_track_rows(std::string& out, std::uint64_t cycle, io::TimeOrigin origin, double time,
                              const std::vector<Track>& tracks) {
  const std::string time_text = io::format_time(origin, time);
  for (const Track& t : tracks) {
    out += std::to_string(cycle);
    out += ',';
    out += time_text;
    out += ',';
    out += std::to_string(t.id);
    out += ',';
    out += t.cluster_id == kNoComponent ? std::string("-1") : std::to_string(t.cluster_id);
    for (const float v : {t.position.x(), t.position.y(), t.position.z(), t.velocity.x(), t.velocity.y(),
                          t.velocity.z(), t.length, t.width, t.height, t.yaw}) {
      out += ',';
      io::detail::append_number(out, v);
    }
    out += ',';
    out += std::to_string(t.points);
    out += ',';
    out += to_string(t.state);
    out += '\n';
  }
}

}  // namespace streamclust::tracking
