// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Internal helper shared by SphericalProjection and CylindricalProjection:
/// the horizontal (azimuth) axis, its field-of-view test and its mapping to u.

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace streamclust {
namespace detail {

/// Build the std::invalid_argument thrown by a policy constructor:
/// "<Policy>: parameter <name> = <value> is invalid; allowed: <allowed>".
inline std::invalid_argument projection_param_error(const char* policy, const char* name, double value,
                                                    const char* allowed) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", value);
  return std::invalid_argument(std::string(policy) + ": parameter " + name + " = " + buf +
                               " is invalid; allowed: " + allowed);
}

/// Azimuth axis of a projection: [min_deg, max_deg] counter-clockwise from
/// min to max, azimuth = atan2(y, x). A span of 360 degrees (tolerance 1e-3
/// degrees) wraps: u is folded into [0, 1) and no point is outside the
/// horizontal FOV. Bounds are inclusive (with a 1e-5 rad tolerance that
/// absorbs float rounding at the edges). Immutable after construction; O(1)
/// and thread-safe.
class AzimuthAxis {
 public:
  static constexpr double kPi = 3.14159265358979323846;
  static constexpr double kWrapToleranceDeg = 1e-3;
  static constexpr float kEdgeToleranceRad = 1e-5f;

  AzimuthAxis() = default;

  /// Validates and precomputes; `policy` names the caller in error messages.
  AzimuthAxis(const char* policy, float min_deg, float max_deg) {
    if (!std::isfinite(min_deg) || min_deg < -360.0f || min_deg > 360.0f)
      throw projection_param_error(policy, "azimuth_min_deg", min_deg, "finite, [-360, 360] degrees");
    if (!std::isfinite(max_deg) || max_deg < -360.0f || max_deg > 720.0f)
      throw projection_param_error(policy, "azimuth_max_deg", max_deg, "finite, [-360, 720] degrees");
    const double span_deg = static_cast<double>(max_deg) - static_cast<double>(min_deg);
    if (!(span_deg > 0.0) || span_deg > 360.0 + kWrapToleranceDeg)
      throw projection_param_error(policy, "azimuth_max_deg - azimuth_min_deg", span_deg, "(0, 360] degrees");
    wraps_ = span_deg >= 360.0 - kWrapToleranceDeg;
    const double span = wraps_ ? 2.0 * kPi : span_deg * kPi / 180.0;
    min_rad_ = static_cast<float>(static_cast<double>(min_deg) * kPi / 180.0);
    span_rad_ = static_cast<float>(span);
    inv_span_ = static_cast<float>(1.0 / span);
    span_deg_ = static_cast<float>(wraps_ ? 360.0 : span_deg);
  }

  bool wraps() const { return wraps_; }
  float span_deg() const { return span_deg_; }
  float span_rad() const { return span_rad_; }

  /// u in [0, 1] (wrapping: [0, 1)) of an azimuth [rad] from atan2, or a
  /// negative value if the azimuth is outside the FOV. O(1).
  float to_u(float azimuth_rad) const {
    constexpr float two_pi = static_cast<float>(2.0 * kPi);
    float d = azimuth_rad - min_rad_;
    if (wraps_) {
      float u = d * inv_span_;
      u -= std::floor(u);
      return u < 1.0f ? u : 0.0f;  // u == 1 after rounding is the seam
    }
    // bring d into [-tol, 2 pi - tol)
    if (d < -kEdgeToleranceRad) d += two_pi;
    if (d < -kEdgeToleranceRad) d += two_pi;  // min_deg may be up to +360
    if (d >= two_pi - kEdgeToleranceRad) d -= two_pi;
    if (d > span_rad_ + kEdgeToleranceRad) return -1.0f;
    const float u = d * inv_span_;
    return u < 0.0f ? 0.0f : (u > 1.0f ? 1.0f : u);
  }

  /// Azimuth [rad] of u (inverse of to_u, not normalised to (-pi, pi]).
  float from_u(float u) const { return min_rad_ + u * span_rad_; }

 private:
  float min_rad_ = 0.0f;
  float span_rad_ = 0.0f;
  float inv_span_ = 0.0f;
  float span_deg_ = 0.0f;
  bool wraps_ = false;
};

}  // namespace detail
}  // namespace streamclust
