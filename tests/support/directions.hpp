// SPDX-License-Identifier: MIT
#pragma once
// Unit directions from azimuth and elevation.

#include "constants.hpp"

#include <Eigen/Core>

#include <cmath>

namespace streamclust::test {

/// Unit direction of azimuth / elevation in degrees (computed in double).
inline Eigen::Vector3f direction_deg(double azimuth_deg, double elevation_deg) {
  const double az = azimuth_deg * kDeg, el = elevation_deg * kDeg;
  return Eigen::Vector3f(static_cast<float>(std::cos(el) * std::cos(az)), static_cast<float>(std::cos(el) * std::sin(az)),
                         static_cast<float>(std::sin(el)));
}

/// Unit direction of azimuth / elevation in radians (computed in float).
inline Eigen::Vector3f spherical(float azimuth, float elevation) {
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation)};
}

}  // namespace streamclust::test
