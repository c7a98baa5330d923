// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The field of view a spherical projection needs in world orientation: with
/// a motion policy the projection sees rays in world orientation (a tilted,
/// upside-down or turning sensor), not in the sensor frame.

#include <streamclust/motion/pose.hpp>
#include <streamclust/projection/spherical.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace streamclust {

/// Projection bounds that hold every direction of `sensor_fov` (azimuth and
/// elevation bounds in the sensor frame) once turned by any of `rotations`
/// (world from sensor: the mount, or the poses of a trajectory), widened by
/// `margin_deg`. The azimuth bounds are the circle minus its largest gap
/// (the full circle when no gap exceeds 2 x margin, or a pole is inside);
/// the minimum range is kept. Directions are sampled on a 1-degree grid of
/// the sensor FOV; rotations are thinned to at most 256 evenly spaced ones
/// (a trajectory's turns are smooth). O(FOV area x rotations).
///
/// \code
/// const auto mount = streamclust::mount_from_roll_pitch_yaw_deg(0.0, 30.0, 0.0);
/// auto fov = streamclust::world_field_of_view(streamclust::field_of_view_of(streamclust::livox_avia),
///                                             {mount.rotation});
/// \endcode
inline SphericalProjection::Params world_field_of_view(const SphericalProjection::Params& sensor_fov,
                                                       const std::vector<Eigen::Quaterniond>& rotations,
                                                       float margin_deg = 1.0f) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const std::size_t stride = rotations.size() > 256 ? (rotations.size() + 255) / 256 : 1;
  std::array<bool, 360> covered{};
  double el_min = 90.0, el_max = -90.0;
  const double az0 = sensor_fov.azimuth_min_deg, az1 = sensor_fov.azimuth_max_deg;
  const double el0 = sensor_fov.elevation_min_deg, el1 = sensor_fov.elevation_max_deg;
  const int az_steps = std::max(1, static_cast<int>(std::ceil(az1 - az0)));
  const int el_steps = std::max(1, static_cast<int>(std::ceil(el1 - el0)));
  auto visit = [&](const Eigen::Quaterniond& q) {
    const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
    for (int i = 0; i <= el_steps; ++i) {
      const double el = (el0 + (el1 - el0) * i / el_steps) * kDeg;
      for (int j = 0; j <= az_steps; ++j) {
        const double az = (az0 + (az1 - az0) * j / az_steps) * kDeg;
        const Eigen::Vector3d d = r * Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
        const double e = std::asin(std::clamp(d.z(), -1.0, 1.0)) / kDeg;
        el_min = std::min(el_min, e);
        el_max = std::max(el_max, e);
        const double a = std::atan2(d.y(), d.x()) / kDeg;  // (-180, 180]
        covered[static_cast<std::size_t>(std::clamp(static_cast<int>(std::floor(a + 180.0)), 0, 359))] = true;
      }
    }
  };
  if (rotations.empty()) visit(Eigen::Quaterniond::Identity());
  for (std::size_t k = 0; k < rotations.size(); k += stride) visit(rotations[k]);
  if (!rotations.empty()) visit(rotations.back());

  SphericalProjection::Params out = sensor_fov;
  out.elevation_min_deg = static_cast<float>(std::max(-90.0, el_min - margin_deg));
  out.elevation_max_deg = static_cast<float>(std::min(90.0, el_max + margin_deg));
  // The largest run of uncovered 1-degree bins, cyclically.
  int best_start = 0, best_length = 0;
  for (int start = 0; start < 360; ++start) {
    if (covered[static_cast<std::size_t>(start)] || !covered[static_cast<std::size_t>((start + 359) % 360)]) continue;
    int length = 0;
    while (length < 360 && !covered[static_cast<std::size_t>((start + length) % 360)]) ++length;
    if (length > best_length) {
      best_length = length;
      best_start = start;
    }
  }
  const bool pole = out.elevation_max_deg >= 89.0f || out.elevation_min_deg <= -89.0f;
  if (pole || static_cast<float>(best_length) <= 2.0f * margin_deg + 1.0f) {
    out.azimuth_min_deg = -180.0f;
    out.azimuth_max_deg = 180.0f;
  } else {
    // Covered: from the gap's end round to its start, margins added.
    double from = best_start + best_length - 180.0 - margin_deg;
    if (from >= 180.0) from -= 360.0;
    double to = best_start - 180.0 + margin_deg;
    while (to <= from) to += 360.0;
    out.azimuth_min_deg = static_cast<float>(from);
    out.azimuth_max_deg = static_cast<float>(to);
  }
  return out;
}

}  // namespace streamclust
