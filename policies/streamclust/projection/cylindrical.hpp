// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// CylindricalProjection: azimuth / height projection.

#include <streamclust/concepts/projection.hpp>
#include <streamclust/detail/fast_atan2.hpp>
#include <streamclust/projection/azimuth_axis.hpp>
#include <streamclust/types.hpp>

#include <Eigen/Core>

#include <cmath>

namespace streamclust {

/// Cylindrical (azimuth x height) projection onto the unit square:
///
/// - azimuth = atan2(y, x), u = (azimuth - azimuth_min) / azimuth_span (as SphericalProjection)
/// - v = (z - z_min) / (z_max - z_min)
///
/// u and v lie in [0, 1]; bounds are inclusive. A 360-degree azimuth span
/// (tolerance 1e-3 degrees) wraps: u is folded into [0, 1) and
/// `wraps_horizontally()` is true.
///
/// Rejection, in this order: non-finite coordinate (or overflowing range) -> `non_finite`; 3D range
/// <= 0 or < min_range -> `too_close` (zero range always); azimuth outside the
/// FOV or z outside [z_min, z_max] -> `outside_fov`.
///
/// `fov_aspect()` = azimuth span [rad] / ((z_max - z_min) / reference_range):
/// the height band is converted to an angle as seen from `reference_range`.
///
/// Complexity: O(1) per point. Thread safety: immutable after construction;
/// `project` is const and may be called concurrently.
///
/// Usage:
/// \code
///   streamclust::CylindricalProjection proj{{-180.0f, 180.0f, -2.0f, 4.0f, 0.1f, 10.0f}};
///   const streamclust::Projected p = proj.project(Eigen::Vector3f(4.0f, 1.0f, 0.5f));
///   const Eigen::Vector3f back = proj.unproject(p.u, p.v, std::hypot(4.0f, 1.0f));
/// \endcode
class CylindricalProjection {
 public:
  /// Parameters (angles in degrees, distances in metres).
  struct Params {
    float azimuth_min_deg = -180.0f;  ///< [deg], in [-360, 360]; azimuth span (max - min) in (0, 360]
    float azimuth_max_deg = 180.0f;   ///< [deg], in [-360, 720]
    float z_min = -3.0f;              ///< [m], lower bound of the height band (sensor frame)
    float z_max = 3.0f;               ///< [m], > z_min
    float min_range = 0.1f;           ///< [m], >= 0; 3D range below it is rejected (too_close)
    float reference_range = 10.0f;    ///< [m], > 0; used only by fov_aspect()
  };

  /// Validates `params`; throws std::invalid_argument naming the parameter,
  /// its value and the allowed range.
  explicit CylindricalProjection(const Params& params)
      : params_(params), azimuth_("CylindricalProjection", params.azimuth_min_deg, params.azimuth_max_deg) {
    constexpr const char* self = "CylindricalProjection";
    if (!std::isfinite(params.z_min)) throw detail::projection_param_error(self, "z_min", params.z_min, "finite [m]");
    if (!std::isfinite(params.z_max) || !(params.z_max > params.z_min) || !std::isfinite(params.z_max - params.z_min))
      throw detail::projection_param_error(self, "z_max", params.z_max, "finite, > z_min [m]");
    if (!std::isfinite(params.min_range) || params.min_range < 0.0f)
      throw detail::projection_param_error(self, "min_range", params.min_range, "finite, >= 0 m");
    if (!std::isfinite(params.reference_range) || !(params.reference_range > 0.0f))
      throw detail::projection_param_error(self, "reference_range", params.reference_range, "finite, > 0 m");
    height_ = params.z_max - params.z_min;
    inv_height_ = 1.0f / height_;
    z_tolerance_ = 1e-6f * height_;
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
    const float range = std::sqrt(x * x + y * y + z * z);
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
    const float dz = z - params_.z_min;
    if (u < 0.0f || dz < -z_tolerance_ || dz > height_ + z_tolerance_) {
      out.reason = RejectReason::outside_fov;
      return out;
    }
    const float v = dz * inv_height_;
    out.u = u;
    out.v = v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
    return out;
  }

  /// Point at horizontal distance `horizontal_distance` [m] from the z axis
  /// with grid coordinates (u, v); the inverse of `project`. O(1).
  Eigen::Vector3f unproject(float u, float v, float horizontal_distance) const {
    const float az = azimuth_.from_u(u);
    return Eigen::Vector3f(horizontal_distance * std::cos(az), horizontal_distance * std::sin(az),
                           params_.z_min + v * height_);
  }

  /// True when the azimuth span is 360 degrees.
  bool wraps_horizontally() const { return azimuth_.wraps(); }

  /// Azimuth span [rad] / ((z_max - z_min) / reference_range).
  float fov_aspect() const { return azimuth_.span_rad() * params_.reference_range / height_; }

  const Params& params() const { return params_; }

 private:
  Params params_;
  detail::AzimuthAxis azimuth_;
  float height_ = 0.0f;
  float inv_height_ = 0.0f;
  float z_tolerance_ = 0.0f;
};

}  // namespace streamclust

static_assert(streamclust::is_projection_policy_v<streamclust::CylindricalProjection>,
              "STREAMCLUST_PROJECTION_POLICY_INVALID: CylindricalProjection");
