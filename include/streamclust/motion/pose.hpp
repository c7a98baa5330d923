// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Rigid poses of the sensor: `Pose` (world from sensor), `StampedPose` (a
/// pose at a stream time), the mount rotation from roll, pitch and yaw, and
/// the interpolation between two poses (linear position, slerp rotation).
///
/// Conventions: a pose maps sensor coordinates to world coordinates,
/// `p_world = rotation * p_sensor + translation`; the world frame has +z up
/// (against gravity). Roll, pitch and yaw are the z-y'-x'' (aerospace)
/// angles: `R = Rz(yaw) * Ry(pitch) * Rx(roll)`; roll 180 degrees is a
/// sensor mounted upside down, a positive pitch tilts the sensor's +x
/// (forward) axis down towards the ground.
///
/// \code
/// const streamclust::Pose mount = streamclust::mount_from_roll_pitch_yaw_deg(0.0, 15.0, 0.0);
/// const Eigen::Vector3d level = mount * Eigen::Vector3d(5.0, 0.0, 0.0);  // a point 5 m ahead, in the level frame
/// \endcode
///
/// Precision: double throughout; the engine stores placed points as float
/// (1 mm up to 8 km from the world origin: give trajectories in a local frame).
/// Thread safety: value types, no shared state.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>

namespace streamclust {

/// World from sensor: `p_world = rotation * p_sensor + translation`.
struct Pose {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  ///< unit quaternion
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();         ///< [m]

  /// The pose applied to a point. O(1).
  Eigen::Vector3d operator*(const Eigen::Vector3d& p) const { return rotation * p + translation; }
  /// Composition: `(a * b) * p == a * (b * p)`. O(1).
  friend Pose operator*(const Pose& a, const Pose& b) {
    return Pose{(a.rotation * b.rotation).normalized(), a.rotation * b.translation + a.translation};
  }
  /// The inverse pose (sensor from world). O(1).
  Pose inverse() const {
    const Eigen::Quaterniond inv = rotation.conjugate();
    return Pose{inv, -(inv * translation)};
  }
};

/// A pose at a stream time [s].
struct StampedPose {
  double time = 0.0;  ///< [s], the points' clock
  Pose pose;
};

/// The rotation `Rz(yaw) * Ry(pitch) * Rx(roll)` of angles in degrees, no
/// translation: a sensor's mount on a level vehicle. O(1).
inline Pose mount_from_roll_pitch_yaw_deg(double roll_deg, double pitch_deg, double yaw_deg) {
  constexpr double deg = 3.14159265358979323846 / 180.0;
  const Eigen::Quaterniond q = Eigen::AngleAxisd(yaw_deg * deg, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pitch_deg * deg, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(roll_deg * deg, Eigen::Vector3d::UnitX());
  return Pose{q.normalized(), Eigen::Vector3d::Zero()};
}

/// The pose a fraction `f` in [0, 1] of the way from `a` to `b`: position
/// linear, rotation by slerp along the shorter arc. O(1).
inline Pose interpolate(const Pose& a, const Pose& b, double f) {
  return Pose{a.rotation.slerp(f, b.rotation).normalized(), a.translation + f * (b.translation - a.translation)};
}

}  // namespace streamclust
