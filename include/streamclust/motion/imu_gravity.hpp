// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The mount's roll and pitch from an accelerometer at rest: it reads the
/// reaction to gravity, 1 g straight up in the sensor frame, so the mean of
/// a window's samples is the sensor's up direction, the same vector the
/// ground-plane search finds as the floor's normal (gravity_estimate.hpp)
/// and converted to angles the same way:
///   up = R^T z for R = Ry(pitch) Rx(roll):
///   roll = atan2(up_y, up_z), pitch = atan2(-up_x, hypot(up_y, up_z)).
/// Yaw is not observable from gravity and stays 0.
///
/// A sensor that moved during the window is refused (nullopt): the mean's
/// magnitude strays from 1 g, or the samples scatter. Pure, O(samples).

#include <streamclust/motion/pose.hpp>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace streamclust {

struct ImuGravityParams {
  std::size_t min_samples = 20;     ///< 0.1 s of a 200 Hz IMU
  double max_magnitude_error = 0.1;  ///< |mean| must lie within 1 +- this [g]
  double max_scatter = 0.1;          ///< RMS distance of the samples from their mean [g]
};

struct ImuGravity {
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  ///< unit vector, sensor frame
  double roll_deg = 0.0, pitch_deg = 0.0;          ///< [deg] of the mount (mount_from_roll_pitch_yaw_deg's)
  double magnitude = 0.0;                          ///< |mean| [g]
  double scatter = 0.0;                            ///< RMS distance of the samples from their mean [g]
  std::size_t samples = 0;
  Pose mount;                                      ///< roll and pitch, yaw 0, no translation
};

/// Roll and pitch from accelerometer samples [g, sensor frame] taken at
/// rest; nullopt with too few samples or a sensor that was not at rest.
inline std::optional<ImuGravity> gravity_from_accelerometer(const std::vector<std::array<float, 3>>& samples,
                                                            const ImuGravityParams& params = {}) {
  if (samples.size() < params.min_samples || samples.empty()) return std::nullopt;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& a : samples) mean += Eigen::Vector3d(a[0], a[1], a[2]);
  mean /= static_cast<double>(samples.size());
  double sum_squares = 0.0;
  for (const auto& a : samples) sum_squares += (Eigen::Vector3d(a[0], a[1], a[2]) - mean).squaredNorm();
  ImuGravity g;
  g.samples = samples.size();
  g.magnitude = mean.norm();
  g.scatter = std::sqrt(sum_squares / static_cast<double>(samples.size()));
  if (!std::isfinite(g.magnitude) || !std::isfinite(g.scatter)) return std::nullopt;
  if (std::abs(g.magnitude - 1.0) > params.max_magnitude_error || g.scatter > params.max_scatter) return std::nullopt;
  g.up = mean / g.magnitude;
  constexpr double deg = 180.0 / 3.14159265358979323846;
  g.roll_deg = std::atan2(g.up.y(), g.up.z()) * deg;
  g.pitch_deg = std::atan2(-g.up.x(), std::hypot(g.up.y(), g.up.z())) * deg;
  g.mount = mount_from_roll_pitch_yaw_deg(g.roll_deg, g.pitch_deg, 0.0);
  return g;
}

}  // namespace streamclust
