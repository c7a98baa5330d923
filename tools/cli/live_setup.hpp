// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What every live source's engine thread does once its first points have
/// come (`live`, `ros2`): the run's time origin from the first point, the
/// driver's input (a LiveReader on the feed), and the run's setup from the
/// first window, with the IMU's gravity for the mount when the source sent
/// accelerations and neither --mount nor --poses was given.

#include "cli/live_feed.hpp"
#include "cli/options.hpp"

#include <streamclust/motion/imu_gravity.hpp>

#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace streamclust::cli {

/// Records the driver's reader hands out between two cycles (the live
/// views' raw points). Owned by the caller for the whole run.
struct LiveTap {
  std::vector<io::Record> records;
  bool on = false;  ///< set once the run is set up (the first window is not tapped)
};

/// How the input is described in the report.
struct LiveInputFields {
  std::vector<std::string> fields = {"x", "y", "z", "reflectivity", "offset_time"};
  std::string time_field = "offset_time";
};

/// Sets `c` up to cluster `feed` (after its wait_for_first returned true):
/// time origin, input named `name`, and in continuous mode the run's setup
/// from the first window; `feed` then keeps no history. `tap` (may be null)
/// receives the records read once set up. `tag` prefixes notes
/// ("streamclust: live"). Returns the IMU's gravity when it was used.
/// Throws UsageError for a setup the first window cannot give.
std::optional<ImuGravity> prepare_live_cluster(ClusterOptions& c, LiveFeed& feed, const std::string& name,
                                               const LiveInputFields& fields, LiveTap* tap, const std::string& tag,
                                               std::ostream& err);

}  // namespace streamclust::cli
