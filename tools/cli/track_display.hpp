// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// How the viewers' outputs show a track (the Foxglove track boxes of
/// `--mcap` and the live view, the ROS 2 node's track markers): confirmed
/// and coasting tracks only, the track id's colour (more transparent while
/// coasting), "ID S.S m/s" above the box, and while it moves an arrow of
/// its ground-plane velocity, 1 s of travel long.

#include "cli/cluster_boxes.hpp"

#include <streamclust/tracking/track.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

namespace streamclust::cli {

struct TrackDisplay {
  std::array<double, 4> rgba{};  ///< colour in [0, 1]; alpha 0.4 confirmed, 0.15 coasting
  std::string text;              ///< "ID S.S m/s": the id and the ground-plane speed
  double arrow_length = 0.0;     ///< [m] the speed (1 s of travel) while moving; else 0: no arrow
  double arrow_yaw = 0.0;        ///< [rad] the heading of the velocity about +z
};

/// True when the viewers show `t`: confirmed or coasting, not tentative.
inline bool shown_track(const tracking::Track& t) { return t.state != tracking::TrackState::tentative; }

/// How the viewers show `t`. O(1).
inline TrackDisplay track_display(const tracking::Track& t) {
  TrackDisplay d;
  const auto c = label_display_color(static_cast<std::int64_t>(t.id));
  d.rgba = {c[0] / 255.0, c[1] / 255.0, c[2] / 255.0, t.state == tracking::TrackState::coasting ? 0.15 : 0.4};
  const double speed = std::hypot(static_cast<double>(t.velocity.x()), static_cast<double>(t.velocity.y()));
  char text[48];
  std::snprintf(text, sizeof text, "%llu %.1f m/s", static_cast<unsigned long long>(t.id), speed);
  d.text = text;
  if (t.moving && speed > 0.0) {
    d.arrow_length = speed;
    d.arrow_yaw = std::atan2(static_cast<double>(t.velocity.y()), static_cast<double>(t.velocity.x()));
  }
  return d;
}

}  // namespace streamclust::cli
