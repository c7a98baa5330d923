// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// TUM records (io/tum.hpp) as stamped poses, ready for PoseTrajectory.
///
/// \code
/// const streamclust::PoseTrajectory trajectory(streamclust::to_stamped_poses(streamclust::io::read_tum("odom.tum")));
/// \endcode
///
/// Thread safety: a free function without shared state.

#include <streamclust/io/tum.hpp>
#include <streamclust/motion/pose.hpp>
#include <streamclust/motion/trajectory.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {

/// One StampedPose per record, in order: time t, translation (tx, ty, tz),
/// rotation (qw, qx, qy, qz) normalised. Throws std::invalid_argument naming
/// the record when a quaternion's norm is below kMinQuaternionNorm (or not
/// finite); other checks are PoseTrajectory's. O(records).
inline std::vector<StampedPose> to_stamped_poses(const std::vector<io::TumRecord>& records) {
  std::vector<StampedPose> poses;
  poses.reserve(records.size());
  for (std::size_t i = 0; i < records.size(); ++i) {
    const io::TumRecord& r = records[i];
    Eigen::Quaterniond q(r.qw, r.qx, r.qy, r.qz);
    const double norm = q.norm();
    if (!(norm >= kMinQuaternionNorm) || !std::isfinite(norm)) {
      throw std::invalid_argument("to_stamped_poses: records[" + std::to_string(i) + "] quaternion norm = " +
                                  std::to_string(norm) + " is invalid; allowed: finite, >= 1e-6");
    }
    q.coeffs() /= norm;
    poses.push_back(StampedPose{r.t, Pose{q, Eigen::Vector3d(r.tx, r.ty, r.tz)}});
  }
  return poses;
}

}  // namespace streamclust
