// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The sensor's mount from its own points: the roll and pitch (yaw 0) that
/// make the ground plane horizontal, for a sensor given neither poses nor a
/// mount. A deterministic RANSAC search for near-horizontal planes.
///
/// The rule. Up to `max_planes` planes are extracted one after the other
/// (each search sees only the points no earlier plane took): each is the
/// 3-point hypothesis with the most inliers (distance <= inlier_distance)
/// among those whose normal lies within `max_tilt_deg` of the sensor's z
/// axis, **either sign**, refined twice by a least-squares fit to its
/// inliers. A plane is *large* when it holds at least `min_plane_fraction`
/// of the points; the search stops at the first plane that is not. The
/// ground is the large plane **nearest to the sensor**; up is its normal
/// pointing towards the sensor. So an upside-down sensor (roll 180) above a
/// floor sees the floor at its -z and finds roll 180; indoors, with floor
/// and ceiling both large, the nearer one wins.
///
/// Failure cases (the estimate is then wrong, or nullopt):
/// - the sensor is nearer to the ceiling than to the floor (a ceiling
///   mount), or the floor is out of view or small while the ceiling is
///   large (a level Mid-360 indoors sees mostly ceiling): the ceiling is
///   taken for the ground and the estimate is upside down;
/// - the sensor is tilted more than `max_tilt_deg`: the ground is no
///   candidate, and a wall then within max_tilt_deg of the z axis is taken
///   for it (raising max_tilt_deg admits walls, and a wall nearer than the
///   ground wins);
/// - a large horizontal surface nearer than the ground (a platform, a big
///   table top) is taken for the ground (its tilt is usually the ground's);
/// - sloped ground is made horizontal: the mount then holds the slope;
/// - no plane holds min_plane_fraction of the points: nullopt. A plane
///   holding a share w of the points is found by `iterations` hypotheses
///   with probability 1 - (1 - w^3)^iterations (w = 0.2: 99.99 % at 2000).
///
/// Cost: O(iterations x max_points x max_planes) point-plane distances
/// (about 10 ms for the defaults), no state; deterministic for a given
/// input and seed (own generator, no std:: distributions).
///
/// \code
/// std::vector<Eigen::Vector3f> first_window = ...;     // sensor frame [m]
/// if (const auto mount = streamclust::estimate_mount(first_window)) params.mount = *mount;
/// \endcode
///
/// Thread safety: free functions without shared state.

#include <streamclust/detail/split_mix.hpp>
#include <streamclust/motion/pose.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {

/// Parameters of estimate_mount / estimate_ground.
struct MountEstimateParams {
  std::size_t iterations = 2000;   ///< RANSAC hypotheses per plane, 1 to 1e6
  double inlier_distance = 0.05;   ///< [m] point-plane distance of an inlier, (0, 10]
  double min_plane_fraction = 0.1;  ///< share of the points a large plane holds, (0, 1]
  double max_tilt_deg = 45.0;      ///< [deg] most angle between a plane's normal and the sensor's z axis, (0, 90)
  std::size_t max_planes = 3;      ///< near-horizontal planes extracted, 1 to 16
  std::size_t max_points = 5000;   ///< points used (an even stride through the finite ones), >= 3
  std::uint64_t seed = 1;          ///< the sampling's seed
};

/// The ground found by estimate_ground.
struct GroundEstimate {
  Pose mount;                                        ///< roll and pitch, yaw 0, no translation: up -> +z
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();     ///< the ground's unit normal towards the sensor, sensor frame
  double height = 0.0;                               ///< [m] the sensor's distance from the ground plane
  double roll_deg = 0.0, pitch_deg = 0.0;            ///< [deg] of the mount (mount_from_roll_pitch_yaw_deg's)
  std::size_t inliers = 0;                           ///< points on the ground plane (among those used)
  std::size_t points_used = 0;                       ///< finite points used
};

namespace detail {


inline void check_mount_estimate_params(const MountEstimateParams& p) {
  const auto fail = [](const char* name, double value, const char* allowed) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", value);
    throw std::invalid_argument(std::string("estimate_mount: parameter ") + name + " = " + buf +
                                " is invalid; allowed: " + allowed);
  };
  if (p.iterations < 1 || p.iterations > 1000000) fail("iterations", static_cast<double>(p.iterations), "1 to 1e6");
  if (!(p.inlier_distance > 0.0 && p.inlier_distance <= 10.0)) fail("inlier_distance", p.inlier_distance, "(0, 10] m");
  if (!(p.min_plane_fraction > 0.0 && p.min_plane_fraction <= 1.0))
    fail("min_plane_fraction", p.min_plane_fraction, "(0, 1]");
  if (!(p.max_tilt_deg > 0.0 && p.max_tilt_deg < 90.0)) fail("max_tilt_deg", p.max_tilt_deg, "(0, 90) deg");
  if (p.max_planes < 1 || p.max_planes > 16) fail("max_planes", static_cast<double>(p.max_planes), "1 to 16");
  if (p.max_points < 3) fail("max_points", static_cast<double>(p.max_points), ">= 3");
}

/// A plane n . p + d = 0 with unit n.
struct Plane {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  double d = 0.0;
};

/// The least-squares plane through `points[idx]` (the normal is the
/// covariance's smallest eigenvector). O(idx).
inline Plane fit_plane(const std::vector<Eigen::Vector3d>& points, const std::vector<std::size_t>& idx) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const std::size_t i : idx) mean += points[i];
  mean /= static_cast<double>(idx.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const std::size_t i : idx) {
    const Eigen::Vector3d q = points[i] - mean;
    cov += q * q.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
  Plane plane;
  plane.n = solver.eigenvectors().col(0).normalized();  // eigenvalues ascending
  plane.d = -plane.n.dot(mean);
  return plane;
}

/// Indexes into `points` of `from` within `distance` of `plane`.
inline void plane_inliers(const std::vector<Eigen::Vector3d>& points, const std::vector<std::size_t>& from,
                          const Plane& plane, double distance, std::vector<std::size_t>& out) {
  out.clear();
  for (const std::size_t i : from) {
    if (std::abs(plane.n.dot(points[i]) + plane.d) <= distance) out.push_back(i);
  }
}

}  // namespace detail

/// The ground plane of `sensor_points` (sensor frame [m]; non-finite points
/// are skipped) by the rule of this header, and the mount that makes it
/// horizontal; nullopt when fewer than 3 finite points or no large
/// near-horizontal plane. Throws std::invalid_argument for bad params.
inline std::optional<GroundEstimate> estimate_ground(const std::vector<Eigen::Vector3f>& sensor_points,
                                                     const MountEstimateParams& params = {}) {
  detail::check_mount_estimate_params(params);
  std::size_t finite = 0;
  for (const Eigen::Vector3f& p : sensor_points) finite += p.allFinite() ? 1u : 0u;
  if (finite < 3) return std::nullopt;
  const std::size_t stride = (finite + params.max_points - 1) / params.max_points;
  std::vector<Eigen::Vector3d> points;
  points.reserve(finite / stride + 1);
  std::size_t k = 0;
  for (const Eigen::Vector3f& p : sensor_points) {
    if (!p.allFinite()) continue;
    if (k++ % stride == 0) points.push_back(p.cast<double>());
  }
  const std::size_t total = points.size();
  const auto large = static_cast<std::size_t>(std::ceil(params.min_plane_fraction * static_cast<double>(total)));
  const double min_abs_nz = std::cos(params.max_tilt_deg * 3.14159265358979323846 / 180.0);

  std::vector<std::size_t> remaining(total);
  for (std::size_t i = 0; i < total; ++i) remaining[i] = i;
  std::vector<std::size_t> inliers, best_inliers, kept;
  detail::SplitMix64 rng{params.seed};
  std::optional<GroundEstimate> ground;

  for (std::size_t plane_no = 0; plane_no < params.max_planes; ++plane_no) {
    const std::size_t m = remaining.size();
    if (m < 3 || m < large) break;
    // RANSAC over near-horizontal 3-point hypotheses.
    std::size_t best = 0;
    detail::Plane best_plane;
    for (std::size_t it = 0; it < params.iterations; ++it) {
      const std::size_t a = rng.below(m), b = rng.below(m), c = rng.below(m);
      if (a == b || b == c || a == c) continue;
      const Eigen::Vector3d& pa = points[remaining[a]];
      const Eigen::Vector3d n = (points[remaining[b]] - pa).cross(points[remaining[c]] - pa);
      const double len = n.norm();
      if (!(len > 1e-12)) continue;
      detail::Plane h{n / len, 0.0};
      if (std::abs(h.n.z()) < min_abs_nz) continue;
      h.d = -h.n.dot(pa);
      std::size_t count = 0;
      for (const std::size_t i : remaining) count += std::abs(h.n.dot(points[i]) + h.d) <= params.inlier_distance;
      if (count > best) {
        best = count;
        best_plane = h;
      }
    }
    if (best < 3 || best < large) break;
    // Two least-squares refinements on the inliers.
    detail::plane_inliers(points, remaining, best_plane, params.inlier_distance, best_inliers);
    detail::Plane plane = best_plane;
    for (int round = 0; round < 2 && best_inliers.size() >= 3; ++round) {
      plane = detail::fit_plane(points, best_inliers);
      detail::plane_inliers(points, remaining, plane, params.inlier_distance, best_inliers);
    }
    if (best_inliers.size() < 3 || best_inliers.size() < large || std::abs(plane.n.z()) < min_abs_nz) break;
    if (plane.d < 0.0) {  // the normal towards the sensor (the origin): n . 0 + d > 0
      plane.n = -plane.n;
      plane.d = -plane.d;
    }
    if (!ground || plane.d < ground->height) {
      GroundEstimate g;
      g.up = plane.n;
      g.height = plane.d;
      g.inliers = best_inliers.size();
      g.points_used = total;
      ground = g;
    }
    // The next search sees the points this plane did not take.
    kept.clear();
    std::size_t j = 0;  // best_inliers is a sorted subsequence of remaining
    for (const std::size_t i : remaining) {
      if (j < best_inliers.size() && best_inliers[j] == i) {
        ++j;
      } else {
        kept.push_back(i);
      }
    }
    remaining.swap(kept);
  }
  if (!ground) return std::nullopt;
  // up = R^T z for R = Ry(pitch) Rx(roll): up = (-sin pitch, sin roll cos pitch, cos roll cos pitch).
  const Eigen::Vector3d& u = ground->up;
  constexpr double deg = 180.0 / 3.14159265358979323846;
  ground->roll_deg = std::atan2(u.y(), u.z()) * deg;
  ground->pitch_deg = std::atan2(-u.x(), std::hypot(u.y(), u.z())) * deg;
  ground->mount = mount_from_roll_pitch_yaw_deg(ground->roll_deg, ground->pitch_deg, 0.0);
  return ground;
}

/// The mount (roll and pitch, yaw 0, no translation) that makes the ground
/// of `sensor_points` horizontal: `estimate_ground(...)->mount`, or nullopt.
inline std::optional<Pose> estimate_mount(const std::vector<Eigen::Vector3f>& sensor_points,
                                          const MountEstimateParams& params = {}) {
  const std::optional<GroundEstimate> ground = estimate_ground(sensor_points, params);
  if (!ground) return std::nullopt;
  return ground->mount;
}

}  // namespace streamclust
