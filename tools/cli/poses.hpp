// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The sensor's poses and mount of `streamclust cluster` (`--poses FILE`,
/// `--mount ROLL,PITCH,YAW`) as the parameters of the PosedMotion policy.

#include "cli/options.hpp"

#include <streamclust/io/odometry_reader.hpp>
#include <streamclust/io/tum.hpp>
#include <streamclust/motion/pose.hpp>
#include <streamclust/motion/posed_motion.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/motion/tum_poses.hpp>

#include <array>
#include <memory>

namespace streamclust::cli {

/// True when the options give poses or a mount (else the stream is in a
/// level sensor frame, or its mount is to be estimated).
inline bool has_motion_options(const ClusterOptions& o) {
  return !o.poses_path.empty() || o.trajectory != nullptr || o.mount_deg.has_value();
}

/// PosedMotion::Params of the options: the mount from `--mount` (identity
/// without it) and the trajectory (the caller's `trajectory`, else read
/// from `--poses`: a TUM file, or the odometry topic of a recording; none
/// without either), its times counted from the input's time origin
/// (`o.read.time_origin`, zero when unset). A malformed file throws
/// io::InputError naming the file and the line (the tool's exit code 4).
/// O(poses).
inline PosedMotion::Params load_motion_params(const ClusterOptions& o) {
  PosedMotion::Params params;
  if (o.mount_deg) {
    const std::array<double, 3>& deg = *o.mount_deg;
    params.mount = mount_from_roll_pitch_yaw_deg(deg[0], deg[1], deg[2]);
  }
  // read_tum checks all PoseTrajectory checks (finite, strictly increasing times, quaternion norm >= 1e-6).
  const io::TimeOrigin origin = o.read.time_origin.value_or(io::TimeOrigin{});
  if (o.trajectory) {
    params.trajectory = o.trajectory;
  } else if (!o.poses_path.empty()) {
    const std::vector<io::TumRecord> records = io::is_odometry_recording(o.poses_path)
                                                   ? io::read_odometry(o.poses_path, origin, o.poses_topic)
                                                   : io::read_tum(o.poses_path, origin);
    params.trajectory = std::make_shared<const PoseTrajectory>(to_stamped_poses(records));
  }
  return params;
}

}  // namespace streamclust::cli
