// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The structure stage of the frame pipeline peer of `streamclust evaluate
/// --objects`, as careful users build it: RANSAC for the ground plane whose
/// candidates must face up (normal near gravity) and lie the known sensor
/// height below the sensor, refitted by least squares on its inliers; then,
/// indoors, the same for the ceiling: a plane facing down onto the sensor
/// from above. A plane that fails its checks, before or after the refit, is
/// not removed.

#include "cli/euclidean_clusters.hpp"
#include "cli/structure_labels.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::cli {

/// What the frame pipeline knows about its sensor and what it accepts as
/// ground or ceiling. A plain aggregate; check() names a bad field.
struct StructurePlaneChecks {
  Eigen::Vector3f up = Eigen::Vector3f::UnitZ();  ///< world up in the sensor frame (unit)
  float sensor_height = 1.0f;                     ///< [m] sensor above the ground
  float max_tilt_deg = 10.0f;                     ///< a plane's normal within this angle of `up`
  float height_tolerance = 0.25f;  ///< [m] the ground plane's distance below the sensor: sensor_height +- this
  float min_ceiling_clearance = 0.3f;   ///< [m] a ceiling at least this far above the sensor ...
  float max_ceiling_clearance = 10.0f;  ///< [m] ... and at most this far
  std::size_t min_ceiling_points = 200;  ///< a ceiling plane needs this many inliers

  /// Throws std::invalid_argument naming the field, its value and the allowed range.
  void check() const {
    const auto fail = [](const char* field, double value, const char* range) {
      throw std::invalid_argument(std::string("StructurePlaneChecks::") + field + " = " + std::to_string(value) +
                                  " is invalid; allowed: " + range);
    };
    if (!(std::abs(up.norm() - 1.0f) < 1e-3f)) fail("up (norm)", static_cast<double>(up.norm()), "a unit vector");
    if (!(sensor_height > 0.0f && sensor_height <= 100.0f)) fail("sensor_height", sensor_height, "(0, 100] m");
    if (!(max_tilt_deg > 0.0f && max_tilt_deg < 90.0f)) fail("max_tilt_deg", max_tilt_deg, "(0, 90) deg");
    if (!(height_tolerance > 0.0f && height_tolerance <= 10.0f)) fail("height_tolerance", height_tolerance, "(0, 10] m");
    if (!(min_ceiling_clearance >= 0.0f && min_ceiling_clearance < max_ceiling_clearance)) {
      fail("min_ceiling_clearance", min_ceiling_clearance, "[0, max_ceiling_clearance)");
    }
  }
};

namespace detail {

/// The plane with normal `normal` (unit, turned to face `up`) through `point`.
inline PlaneFit plane_facing(Eigen::Vector3f normal, const Eigen::Vector3f& point, const Eigen::Vector3f& up) {
  if (normal.dot(up) < 0.0f) normal = -normal;
  return PlaneFit{normal, -normal.dot(point), 0, true};
}

/// Points within `distance` of the plane. O(n).
inline std::size_t count_inliers(const std::vector<Eigen::Vector3f>& points, const std::vector<std::size_t>& subset,
                                 const PlaneFit& plane, float distance) {
  std::size_t inliers = 0;
  for (const std::size_t i : subset) inliers += std::abs(plane.normal.dot(points[i]) + plane.offset) <= distance ? 1u : 0u;
  return inliers;
}

/// The least-squares plane of the inliers of `plane` (the normal is the
/// covariance's eigenvector of the smallest eigenvalue), facing `up`; the
/// input plane when fewer than 3 inliers. O(n).
inline PlaneFit refit_plane(const std::vector<Eigen::Vector3f>& points, const std::vector<std::size_t>& subset,
                            const PlaneFit& plane, float distance, const Eigen::Vector3f& up) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  std::size_t n = 0;
  for (const std::size_t i : subset) {
    if (!(std::abs(plane.normal.dot(points[i]) + plane.offset) <= distance)) continue;
    const Eigen::Vector3d p = points[i].cast<double>();
    sum += p;
    outer += p * p.transpose();
    ++n;
  }
  if (n < 3) return plane;
  const Eigen::Vector3d mean = sum / static_cast<double>(n);
  const Eigen::Matrix3d covariance = outer / static_cast<double>(n) - mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3f normal = solver.eigenvectors().col(0).cast<float>().normalized();
  if (!normal.allFinite()) return plane;
  return plane_facing(normal, mean.cast<float>(), up);
}

}  // namespace detail

/// RANSAC for the plane of `subset` (indices into `points`) with the most
/// inliers among those `accept(plane)` allows (PCL's perpendicular-plane
/// model with its own check): draws of three distinct points (a generator
/// seeded with `seed`) until `iterations` candidates passed `accept` or 20
/// times as many draws were made; each accepted candidate (normal facing
/// `up`) scored by its points within `distance`; the best refitted by least
/// squares on its inliers (PCL's model refinement). Not found when no
/// candidate passed or the refit fails `accept`; else the refit, its
/// inliers counted. O(iterations n).
template <class Accept>
PlaneFit ransac_checked_plane(const std::vector<Eigen::Vector3f>& points, const std::vector<std::size_t>& subset,
                              float distance, std::size_t iterations, std::uint64_t seed, const Eigen::Vector3f& up,
                              Accept&& accept) {
  PlaneFit best;
  const std::size_t n = subset.size();
  if (n < 3) return best;
  std::mt19937_64 rng(seed);  // raw draws only: the same sequence on every standard library
  std::size_t accepted = 0;
  for (std::size_t draw = 0; accepted < iterations && draw < 20 * iterations; ++draw) {
    const Eigen::Vector3f& a = points[subset[static_cast<std::size_t>(rng() % n)]];
    const Eigen::Vector3f& b = points[subset[static_cast<std::size_t>(rng() % n)]];
    const Eigen::Vector3f& c = points[subset[static_cast<std::size_t>(rng() % n)]];
    const Eigen::Vector3f u = b - a;
    const Eigen::Vector3f v = c - a;
    const Eigen::Vector3f normal = u.cross(v);
    const float norm = normal.norm();
    if (!(norm > 1e-6f * u.norm() * v.norm()) || !std::isfinite(norm)) continue;  // collinear or repeated
    PlaneFit candidate = detail::plane_facing(normal / norm, a, up);
    if (!accept(candidate)) continue;
    ++accepted;
    candidate.inliers = detail::count_inliers(points, subset, candidate, distance);
    if (!best.found || candidate.inliers > best.inliers) best = candidate;
  }
  if (!best.found) return best;
  // A candidate that crosses a surface at an angle (a strip of a ground
  // lower than the sensor height, say) refits onto that surface and fails.
  PlaneFit refit = detail::refit_plane(points, subset, best, distance, up);
  if (!accept(refit)) return PlaneFit{};
  refit.inliers = detail::count_inliers(points, subset, refit, distance);
  return refit;
}

/// The ground and ceiling planes the frame pipeline removed (found = false:
/// none passed the checks, nothing removed).
struct StructurePlanes {
  PlaneFit ground;
  PlaneFit ceiling;
};

/// The frame pipeline's structure stage on one window of sensor-frame
/// points: the ground plane (found among the points at least sensor_height
/// - height_tolerance - distance below the sensor; normal within
/// max_tilt_deg of `up`, the sensor sensor_height +- height_tolerance above
/// it), its points within `distance` labelled kGroundLabel (-2); with
/// `ceiling`, then on the rest a ceiling plane (found among the points at
/// least min_ceiling_clearance - distance above the sensor; normal near
/// `up`, min..max_ceiling_clearance above the sensor, >= min_ceiling_points
/// inliers), its points labelled kCeilingLabel (-3). Every other point gets -1 (left to clustering).
/// Deterministic for a seed. O(iterations n). Throws std::invalid_argument
/// for bad checks, a distance outside (0, 10] m or iterations outside [1,
/// 100000].
inline StructurePlanes classify_structure_planes(const std::vector<Eigen::Vector3f>& points, float distance,
                                                 std::size_t iterations, std::uint64_t seed,
                                                 const StructurePlaneChecks& checks, bool ceiling,
                                                 std::vector<std::int64_t>& labels) {
  checks.check();
  if (!(distance > 0.0f) || !(distance <= 10.0f)) {
    throw std::invalid_argument("classify_structure_planes: distance = " + std::to_string(distance) +
                                " is invalid; allowed: (0, 10] m");
  }
  if (iterations < 1 || iterations > 100000) {
    throw std::invalid_argument("classify_structure_planes: iterations = " + std::to_string(iterations) +
                                " is invalid; allowed: [1, 100000]");
  }
  constexpr float kDegree = 3.14159265358979323846f / 180.0f;
  const float min_cos = std::cos(checks.max_tilt_deg * kDegree);
  const Eigen::Vector3f& up = checks.up;
  // n . p + d = 0 with n facing up: d is the sensor's height above the plane.
  const auto is_ground = [&](const PlaneFit& p) {
    return p.normal.dot(up) >= min_cos && std::abs(p.offset - checks.sensor_height) <= checks.height_tolerance;
  };
  const auto is_ceiling = [&](const PlaneFit& p) {
    return p.normal.dot(up) >= min_cos && -p.offset >= checks.min_ceiling_clearance &&
           -p.offset <= checks.max_ceiling_clearance;
  };
  const std::size_t n = points.size();
  labels.assign(n, -1);
  std::vector<std::size_t> rest;
  rest.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (points[i].allFinite()) rest.push_back(i);
  }
  StructurePlanes planes;
  // Each plane is searched among the points on its side of the sensor (a
  // pass-through filter on the height along `up`), then removed from all.
  std::vector<std::size_t> candidates;
  const auto candidates_where = [&](auto&& keep) {
    candidates.clear();
    for (const std::size_t i : rest) {
      if (keep(points[i].dot(up))) candidates.push_back(i);
    }
    return candidates;
  };
  const auto remove = [&](const PlaneFit& plane, std::int64_t label) {
    std::size_t kept = 0;
    for (const std::size_t i : rest) {
      if (std::abs(plane.normal.dot(points[i]) + plane.offset) <= distance) {
        labels[i] = label;
      } else {
        rest[kept++] = i;
      }
    }
    rest.resize(kept);
  };
  const float below = checks.sensor_height - checks.height_tolerance - distance;  // [m] under the sensor
  planes.ground = ransac_checked_plane(points, candidates_where([&](float height) { return height <= -below; }),
                                       distance, iterations, seed, up, is_ground);
  if (planes.ground.found) remove(planes.ground, kGroundLabel);
  if (ceiling) {
    const float above = checks.min_ceiling_clearance - distance;  // [m] over the sensor
    planes.ceiling = ransac_checked_plane(points, candidates_where([&](float height) { return height >= above; }),
                                          distance, iterations, seed + 1, up, is_ceiling);
    if (planes.ceiling.found && planes.ceiling.inliers < checks.min_ceiling_points) planes.ceiling = PlaneFit{};
    if (planes.ceiling.found) remove(planes.ceiling, kCeilingLabel);
  }
  return planes;
}

}  // namespace streamclust::cli
