// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// SphericalProjection: azimuth / elevation range-image projection.

#include <streamclust/concepts/projection.hpp>
#include <streamclust/detail/fast_atan2.hpp>
#include <streamclust/projection/azimuth_axis.hpp>
#include <streamclust/types.hpp>

#include <Eigen/Core>

#include <cmath>

namespace streamclust {

/// Spherical (azimuth x elevation) projection of sensor-frame points onto the
/// unit square, the usual range-image geometry.
///
/// - azimuth   = atan2(y, x), u = (azimuth - azimuth_min) / azimuth_span
/// - elevation = atan2(z, hypot(x, y)), v = (elevation - elevation_min) / elevation_span
///
/// Both u and v lie in [0, 1]; FOV bounds are inclusive. When the azimuth
/// span is 360 degrees (tolerance 1e-3 degrees) `wraps_horizontally()` is true
/// and u is folded into [0, 1): azimuth +180 and -180 degrees both give u = 0
/// (the seam), so the spatial index treats column 0 and the last column as
/// neighbours.
///
/// Rejection, checked in this order:
/// 1. any NaN / infinite coordinate (or a range that overflows float) -> `RejectReason::non_finite`
/// 2. range <= 0 or range < min_range -> `RejectReason::too_close` (a zero-range
///    point is always rejected, even with min_range = 0: it has no direction)
/// 3. azimuth or elevation outside the FOV -> `RejectReason::outside_fov`
///
/// Complexity: O(1) per point (two sqrt, two polynomial atan2, detail::fast_atan2). No allocation.
/// Thread safety: immutable after construction; `project` is const and may be
/// called concurrently.
///
/// Usage:
/// \code
///   streamclust::SphericalProjection proj{{-180.0f, 180.0f, -7.0f, 52.0f, 0.1f}};  // Livox Mid-360
///   const streamclust::Projected p = proj.project(Eigen::Vector3f(4.0f, 1.0f, 0.5f));
///   if (p.accepted()) { /* p.u, p.v in [0, 1], p.range in m */ }
///   const Eigen::Vector3f back = proj.unproject(p.u, p.v, p.range);  // ~ the input point
/// \endcode
class SphericalProjection {
 public:
  /// Parameters (angles in degrees, distances in metres).
  struct Params {
    float azimuth_min_deg = -180.0f;   ///< [deg], in [-360, 360]; azimuth span (max - min) in (0, 360]
    float azimuth_max_deg = 180.0f;    ///< [deg], in [-360, 720]
    float elevation_min_deg = -90.0f;  ///< [deg], within [-90, 90]
    float elevation_max_deg = 90.0f;   ///< [deg], within [-90, 90], > elevation_min_deg
    float min_range = 0.1f;            ///< [m], >= 0; closer points are rejected (too_close)
  };

  /// Validates `params`; throws std::invalid_argument naming the parameter,
  /// its value and the allowed range.
  explicit SphericalProjection(const Params& params)
      : params_(params), azimuth_("SphericalProjection", params.azimuth_min_deg, params.azimuth_max_deg) {
    constexpr const char* self = "SphericalProjection";
    if (!std::isfinite(params.elevation_min_deg) || params.elevation_min_deg < -90.0f ||
        params.elevation_min_deg > 90.0f)
      throw detail::projection_param_error(self, "elevation_min_deg", params.elevation_min_deg,
                                           "finite, [-90, 90] degrees");
    if (!std::isfinite(params.elevation_max_deg) || params.elevation_max_deg < -90.0f ||
        params.elevation_max_deg > 90.0f)
      throw detail::projection_param_error(self, "elevation_max_deg", params.elevation_max_deg,
                                           "finite, [-90, 90] degrees");
    if (!(params.elevation_max_deg > params.elevation_min_deg))
      throw detail::projection_param_error(
          self, "elevation_max_deg - elevation_min_deg",
          static_cast<double>(params.elevation_max_deg) - static_cast<double>(params.elevation_min_deg),
          "(0, 180] degrees");
    if (!std::isfinite(params.min_range) || params.min_range < 0.0f)
      throw detail::projection_param_error(self, "min_range", params.min_range, "finite, >= 0 m");
    constexpr double deg = detail::AzimuthAxis::kPi / 180.0;
    el_min_rad_ = static_cast<float>(static_cast<double>(params.elevation_min_deg) * deg);
    const double el_span = (static_cast<double>(params.elevation_max_deg) - params.elevation_min_deg) * deg;
    el_span_rad_ = static_cast<float>(el_span);
    el_inv_span_ = static_cast<float>(1.0 / el_span);
    el_span_deg_ = params.elevation_max_deg - params.elevation_min_deg;
  }

  /// Project a sensor-frame position [m]. O(1), const, thread-safe.
  Projected project(const Eigen::Vector3f& position) const {
    Projected out;
    const float x = position.x();
    const float y = position.y();
    const float z = position.z();
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
      out.reason = RejectReason::non_finite;
      return out;
    }
    const float horizontal_sq = x * x + y * y;
    const float horizontal = std::sqrt(horizontal_sq);
    const float range = std::sqrt(horizontal_sq + z * z);
    out.range = range;
    if (!std::isfinite(range)) {  // |position| overflows float (coordinates beyond ~1.8e19 m)
      out.reason = RejectReason::non_finite;
      return out;
    }
    if (!(range > 0.0f) || range < params_.min_range) {
      out.reason = RejectReason::too_close;
      return out;
    }
    const float u = azimuth_.to_u(detail::fast_atan2(y, x));
    const float v = elevation_to_v(detail::fast_atan2(z, horizontal));
    if (u < 0.0f || v < 0.0f) {
      out.reason = RejectReason::outside_fov;
      return out;
    }
    out.u = u;
    out.v = v;
    return out;
  }

  /// Point at `range` [m] along the ray of grid coordinates (u, v); the
  /// inverse of `project` (for tests and visualisation). O(1).
  Eigen::Vector3f unproject(float u, float v, float range) const {
    const float az = azimuth_.from_u(u);
    const float el = el_min_rad_ + v * el_span_rad_;
    const float c = std::cos(el);
    return Eigen::Vector3f(range * c * std::cos(az), range * c * std::sin(az), range * std::sin(el));
  }

  /// True when the azimuth span is 360 degrees (u = 0 and u = 1 are neighbours).
  bool wraps_horizontally() const { return azimuth_.wraps(); }

  /// Azimuth span / elevation span (both in degrees).
  float fov_aspect() const { return azimuth_.span_deg() / el_span_deg_; }

  const Params& params() const { return params_; }

 private:
  /// v in [0, 1], or -1 when outside the elevation bounds (inclusive, with a
  /// 1e-5 rad tolerance for float rounding at the edges).
  float elevation_to_v(float el) const {
    const float d = el - el_min_rad_;
    if (d < -detail::AzimuthAxis::kEdgeToleranceRad ||
        d > el_span_rad_ + detail::AzimuthAxis::kEdgeToleranceRad)
      return -1.0f;
    const float v = d * el_inv_span_;
    return v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
  }

  Params params_;
  detail::AzimuthAxis azimuth_;
  float el_min_rad_ = 0.0f;
  float el_span_rad_ = 0.0f;
  float el_inv_span_ = 0.0f;
  float el_span_deg_ = 0.0f;
};

}  // namespace streamclust

static_assert(streamclust::is_projection_policy_v<streamclust::SphericalProjection>,
              "STREAMCLUST_PROJECTION_POLICY_INVALID: SphericalProjection");
