// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// ScanAdaptiveLinkage: a Euclidean radius that follows the sensor's local
/// angular spacing of returns at the point's direction, and its range.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/detail/blocks_of_four.hpp>
#include <streamclust/detail/hints.hpp>
#include <streamclust/detail/rounded.hpp>
#include <streamclust/linkage/scan_spacing.hpp>
#include <streamclust/motion/pose.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/sensor_fit.hpp>
#include <streamclust/types.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

namespace streamclust {

/// Links a and b iff
///
///     |a.position - b.position| <= min(radius(a), radius(b))
///     radius(p) = max(min_distance, spacing_factor * spacing(direction_sensor(p)) * p.range)
///
/// spacing(d) [rad] is the sensor's gap between neighbouring returns of one
/// window at sensor-frame direction d (ScanSpacing: a quantile of the
/// spanning-tree edges of the window's directions there, a table fixed
/// before the engine starts), so the radius is a few such gaps where the
/// point is: tight in the Avia's dense centre, wide at its rim and in the
/// Mid-360's sparse bands, where RangeAdaptiveLinkage has one angle
/// (range_factor) for every direction. The smaller radius decides (min),
/// as RangeAdaptiveLinkage's nearer range does. Defaults and the objects
/// evaluation: docs/design-decisions.md (a radius that follows the scan).
///
/// Sensor frame: the scan pattern is fixed to the sensor, the Sample's
/// direction is in world orientation (a motion policy placed it). The
/// linkage turns it back with the sensor's rotation at the Sample's time:
/// `mount` alone, or `trajectory(t) * mount` (the PosedMotion parameters;
/// times outside the trajectory take its end poses, which the engine
/// rejects anyway).
///
/// Payload: position and the point's radius (16 bytes), a *bound* payload
/// (concepts/linkage.hpp): `make_payload` is a const member that reads the
/// table and the rotation once per point, at insertion (a quaternion slerp
/// with a trajectory, two inverse trigonometric functions and a bilinear
/// read; one function, never inlined, so that every caller computes the
/// same radius bit for bit). The Sample operator is the payload operator
/// on `make_payload(a)`, `make_payload(b)`; the batch oracle built from the
/// same Params therefore decides exactly as the engine.
///
/// Exactly symmetric, bit for bit: min of the two radii, the squared
/// coordinate differences summed in one fixed order with every product
/// rounded on its own (detail/rounded.hpp). `link_many` tests four
/// candidates at a time with SSE2, the pairwise operations in their order.
///
/// Parameters are fitted before the engine starts: give `spacing` (e.g.
/// ScanSpacing::from_sensor_model for a simulated sensor, or
/// from_directions on a recording's first window), or call
/// `fit_to_sensor` (sensor_fit.hpp), which builds the table from the first
/// window and takes the mount and poses; the tool does that.
///
/// Complexity: O(1) per pair (three differences, three squares, a min, no
/// sqrt); O(1) per point for the payload (O(log poses) with a trajectory).
/// Thread safety: immutable; const members are thread-safe; the table and
/// trajectory are shared read-only.
///
/// Usage:
/// \code
///   streamclust::sim::AviaModel avia;
///   streamclust::ScanAdaptiveLinkage::Params p;
///   p.spacing = streamclust::ScanSpacing::from_sensor_model(avia, 0.5);  // T_B = 0.5 s
///   p.mount = streamclust::mount_from_roll_pitch_yaw_deg(0.0, 15.0, 0.0);
///   streamclust::ScanAdaptiveLinkage link{p};
///   bool joined = link(sample_a, sample_b);
///   float r = link.radius(sample_a);  // [m]
/// \endcode
class ScanAdaptiveLinkage {
 public:
  struct Params {
    /// [m] radius near the sensor (the floor), finite, in (0, 100]
    float min_distance = 0.4f;
    /// [1] the radius in local spacings of the returns, finite, in (0, 1000]
    float spacing_factor = 4.0f;
    /// the sensor's spacing table (sensor frame, one window T_B); required
    /// (fit_to_sensor builds it when null)
    std::shared_ptr<const ScanSpacing> spacing;
    /// how fit_to_sensor builds `spacing` from a first window: the
    /// quantile of the spanning-tree edges a cell keeps (ScanSpacing), in [0, 1]
    float spacing_quantile = ScanSpacing::Params{}.quantile;
    /// ... and its cells' side [deg], in [0.25, 10]
    float spacing_cell_deg = ScanSpacing::Params{}.cell_deg;
    Pose mount;  ///< vehicle (or world) from sensor, as PosedMotion's; identity: the sensor frame is the world's
    std::shared_ptr<const PoseTrajectory> trajectory;  ///< world from vehicle over time; null: the mount alone
  };

  /// Throws std::invalid_argument naming the parameter, its value and the
  /// allowed range.
  explicit ScanAdaptiveLinkage(const Params& params) : params_(params) {
    if (!std::isfinite(params.min_distance) || !(params.min_distance > 0.0f) || params.min_distance > 100.0f)
      throw error("min_distance", params.min_distance, "finite, in (0, 100] m");
    if (!std::isfinite(params.spacing_factor) || !(params.spacing_factor > 0.0f) || params.spacing_factor > 1000.0f)
      throw error("spacing_factor", params.spacing_factor, "finite, in (0, 1000]");
    if (!params.spacing)
      throw std::invalid_argument("ScanAdaptiveLinkage: parameter spacing is null; allowed: a ScanSpacing table "
                                  "(ScanSpacing::from_directions or from_sensor_model, or fit_to_sensor)");
    const Eigen::Vector4d q = params.mount.rotation.coeffs();
    if (!q.allFinite() || q.norm() < kMinQuaternionNorm)
      throw error("mount.rotation norm", q.norm(), "finite quaternion components, norm >= 1e-6");
    params_.mount.rotation.normalize();
    sensor_from_mount_ = params_.mount.rotation.conjugate();
  }

  /// `params` with the mount and poses of `fit`, and, when `params.spacing`
  /// is null, the table of fit.first_window (ScanSpacing::from_directions
  /// with spacing_quantile and spacing_cell_deg). Throws
  /// std::invalid_argument from the table. O(first window).
  static Params fit_to_sensor(const Params& params, const SensorFit& fit) {
    Params p = params;
    if (!p.spacing) {
      ScanSpacing::Params table;
      table.quantile = p.spacing_quantile;
      table.cell_deg = p.spacing_cell_deg;
      p.spacing = ScanSpacing::from_directions(fit.first_window, table);
    }
    p.mount = fit.mount;
    p.trajectory = fit.trajectory;
    return p;
  }

  /// What the criterion reads of a point: position and radius. 16 bytes,
  /// 16-aligned, trivially copyable.
  struct alignas(16) Payload {
    float position[3];  ///< [m] Sample::position
    float radius;       ///< [m] radius(sample)
  };

  /// The payload of `s`: its position and radius(s). O(1) (see radius).
  Payload make_payload(const Sample& s) const {
    return Payload{{s.position.x(), s.position.y(), s.position.z()}, radius(s)};
  }

  /// The link radius of `s` [m]: max(min_distance, spacing_factor *
  /// spacing(sensor direction) * range). Never inlined (one computation for
  /// every caller, bit for bit). O(1); O(log poses) with a trajectory.
  STREAMCLUST_NOINLINE float radius(const Sample& s) const {
    const float spacing = params_.spacing->at(sensor_direction(s));
    return std::max(params_.min_distance, detail::rounded(params_.spacing_factor * spacing) * s.range);
  }

  /// The direction of `s` in the sensor frame at its time (unit). O(1);
  /// O(log poses) with a trajectory.
  Eigen::Vector3f sensor_direction(const Sample& s) const {
    Eigen::Quaterniond sensor_from_world = sensor_from_mount_;
    if (const PoseTrajectory* trajectory = params_.trajectory.get()) {
      const double t = std::clamp(s.time, trajectory->time_begin(), trajectory->time_end());
      PoseTrajectory::Cursor cursor;
      const std::optional<Pose> vehicle = trajectory->at(std::isfinite(t) ? t : trajectory->time_begin(), cursor);
      sensor_from_world = sensor_from_mount_ * vehicle->rotation.conjugate();
    }
    return (sensor_from_world * s.direction.cast<double>()).cast<float>();
  }

  /// True iff |a - b| <= min(radius(a), radius(b)). O(1) plus two payloads.
  bool operator()(const Sample& a, const Sample& b) const { return (*this)(make_payload(a), make_payload(b)); }

  /// True iff |a - b| <= min(a.radius, b.radius), compared squared. O(1).
  STREAMCLUST_ALWAYS_INLINE bool operator()(const Payload& a, const Payload& b) const {
    using detail::rounded;  // every product that feeds a sum: never fused (detail/rounded.hpp)
    const float dx = a.position[0] - b.position[0];
    const float dy = a.position[1] - b.position[1];
    const float dz = a.position[2] - b.position[2];
    const float squared = (rounded(dx * dx) + rounded(dy * dy)) + rounded(dz * dz);
    const float r = std::min(a.radius, b.radius);
    return squared <= r * r;
  }

  /// Optional capability (concepts/linkage.hpp): linked[k] = (*this)(a,
  /// ring[slots[k]]) for k < count. With SSE2 four candidates at a time (the
  /// last count % 4 padded with repeats of their first slot), the pairwise
  /// operator's operations in its order; without SSE2 the pairwise
  /// operator. O(count).
  void link_many(const Payload& a, const Payload* ring, const std::uint32_t* slots, std::size_t count,
                 std::uint8_t* linked) const {
#if defined(__SSE2__)
    const Lanes lanes(a);
    detail::in_blocks_of_four(slots, count, linked, [&](const std::uint32_t* four, std::uint8_t* out) {
      link_four(lanes, ring, four, out);
    });
#else
    for (std::size_t k = 0; k < count; ++k) linked[k] = (*this)(a, ring[slots[k]]) ? 1u : 0u;
#endif
  }

  const Params& params() const { return params_; }
  const ScanSpacing& spacing() const { return *params_.spacing; }

 private:
#if defined(__SSE2__)
  /// link_many's subject, one copy per SSE lane.
  struct Lanes {
    __m128 ax, ay, az, ar;
    explicit Lanes(const Payload& a)
        : ax(_mm_set1_ps(a.position[0])),
          ay(_mm_set1_ps(a.position[1])),
          az(_mm_set1_ps(a.position[2])),
          ar(_mm_set1_ps(a.radius)) {}
  };

  /// linked[i] = the decision of the subject in `l` against ring[slots[i]],
  /// for i < 4: the pairwise operator, lane by lane. O(1).
  STREAMCLUST_ALWAYS_INLINE static void link_four(const Lanes& l, const Payload* ring, const std::uint32_t* slots,
                                                  std::uint8_t* linked) {
    const detail::FourColumns b = detail::load_four_columns(ring, slots);  // x, y, z, radius
    const __m128 squared = detail::squared_distances_four(l.ax, l.ay, l.az, b);
    // std::min(ra, rb): minps gives the same value on finite radii (> 0).
    const __m128 r = _mm_min_ps(l.ar, b.w);
    detail::store_four_decisions(_mm_movemask_ps(_mm_cmple_ps(squared, _mm_mul_ps(r, r))), linked);
  }
#endif

  static std::invalid_argument error(const char* name, double value, const char* allowed) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", value);
    return std::invalid_argument(std::string("ScanAdaptiveLinkage: parameter ") + name + " = " + buf +
                                 " is invalid; allowed: " + allowed);
  }

  Params params_;
  Eigen::Quaterniond sensor_from_mount_ = Eigen::Quaterniond::Identity();  ///< mount.rotation^-1
};

}  // namespace streamclust

static_assert(streamclust::is_linkage_policy_v<streamclust::ScanAdaptiveLinkage>,
              "STREAMCLUST_LINKAGE_POLICY_INVALID: ScanAdaptiveLinkage");
static_assert(streamclust::has_linkage_bound_payload_v<streamclust::ScanAdaptiveLinkage> &&
                  streamclust::is_linkage_payload_valid_v<streamclust::ScanAdaptiveLinkage> &&
                  streamclust::has_linkage_link_many_v<streamclust::ScanAdaptiveLinkage> &&
                  !streamclust::has_linkage_ray_payload_v<streamclust::ScanAdaptiveLinkage> &&
                  sizeof(streamclust::ScanAdaptiveLinkage::Payload) == 16,
              "STREAMCLUST_LINKAGE_PAYLOAD_INVALID: ScanAdaptiveLinkage");
static_assert(streamclust::has_sensor_fit_v<streamclust::ScanAdaptiveLinkage>,
              "STREAMCLUST_LINKAGE_POLICY_INVALID: ScanAdaptiveLinkage::fit_to_sensor");
