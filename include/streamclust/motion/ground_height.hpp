// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The sensor's height above the ground from its first window when its
/// orientation is known (poses, a mount, an IMU): no plane search in the
/// sensor frame, no floor-or-ceiling question, only where the ground lies
/// below the sensor.

#include <streamclust/detail/split_mix.hpp>

#include <Eigen/Core>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

namespace streamclust {

/// Parameters of estimate_ground_height (metres, degrees).
struct GroundHeightParams {
  double cell = 1.0;              ///< [m] horizontal cell edge
  double max_distance = 12.0;     ///< [m] cells this far from the sensor, horizontally, at most (rolling ground: 20 m put the plane 0.1-0.35 m off)
  std::size_t layer_points = 5;   ///< a cell's flat lowest layer holds this many points at least
  double layer_thickness = 0.05;  ///< [m] within this height
  double inlier_distance = 0.08;  ///< [m] a cell's layer this close to a plane lies on it
  double max_tilt_deg = 20.0;     ///< [deg] steepest ground plane
  std::size_t min_cells = 6;      ///< a ground plane holds this many cells at least
  int iterations = 300;           ///< RANSAC draws per plane
  int max_planes = 3;             ///< planes extracted one after the other
};

/// The estimate: the sensor's height above the ground plane under it.
struct GroundHeightEstimate {
  double height = 0.0;         ///< [m] from the ground plane, at the sensor's foot, up to the sensor
  std::size_t cells = 0;       ///< cells with a flat lowest layer
  std::size_t plane_cells = 0; ///< of those, on the chosen plane
};

/// The ground under a sensor whose points of one window are given as
/// `rays`: each point minus the sensor's position when it was captured, in
/// world orientation (+z against gravity). The rule: per cell within
/// `max_distance` (horizontally) its flat lowest layer (the lowest
/// `layer_points` points within `layer_thickness`; a cell without one: an
/// object's side, noise) gives one point, the layer's mean; planes tilted at
/// most `max_tilt_deg` are extracted one after the other (RANSAC over those
/// points, deterministic, refined by least squares on the inliers); of the
/// planes with at least `min_cells` cells and a quarter of the largest's,
/// the lowest under the sensor is the ground (a road below its sidewalks, a
/// floor below the desk tops). Nullopt when no plane qualifies. O(points +
/// cells x iterations x planes); no state. Measured on the simulated office,
/// forest, street and hills, Mid-360 and Avia, level, pitched 15 and 30 deg
/// and upside down: within 5 % of the height, but a level Mid-360 on the
/// hills (0.85 for 1 m: it sees the ground from 8 m on). It needs ground in
/// view within `max_distance`: a level Mid-360 1.5 m up in the office sees
/// the floor only from 12 m on, and the desk tops come out as the ground
/// (0.90 m for 1.5).
inline std::optional<GroundHeightEstimate> estimate_ground_height(const std::vector<Eigen::Vector3f>& rays,
                                                                  const GroundHeightParams& params = {}) {
  struct CellPoints {
    std::vector<Eigen::Vector3f> points;
  };
  std::unordered_map<std::uint64_t, CellPoints> cells;
  for (const Eigen::Vector3f& r : rays) {
    if (!r.allFinite() || r.z() >= 0.0f) continue;  // ground below the sensor
    const double d = std::hypot(static_cast<double>(r.x()), static_cast<double>(r.y()));
    if (d > params.max_distance) continue;
    const auto ix = static_cast<std::int64_t>(std::floor(r.x() / params.cell));
    const auto iy = static_cast<std::int64_t>(std::floor(r.y() / params.cell));
    cells[(static_cast<std::uint64_t>(ix) << 32) ^ (static_cast<std::uint64_t>(iy) & 0xffffffffu)].points.push_back(r);
  }
  // Each cell's flat lowest layer.
  std::vector<Eigen::Vector3d> layers;
  for (auto& [key, cell] : cells) {
    std::vector<Eigen::Vector3f>& p = cell.points;
    if (p.size() < params.layer_points) continue;
    std::sort(p.begin(), p.end(), [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) { return a.z() < b.z(); });
    for (std::size_t i = 0; i + params.layer_points <= p.size(); ++i) {
      if (p[i + params.layer_points - 1].z() - p[i].z() > params.layer_thickness) continue;
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      std::size_t n = 0;
      for (std::size_t j = i; j < p.size() && p[j].z() - p[i].z() <= params.layer_thickness; ++j, ++n) {
        sum += p[j].cast<double>();
      }
      layers.push_back(sum / static_cast<double>(n));
      break;
    }
  }
  // Deterministic order (the map's is not).
  std::sort(layers.begin(), layers.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() != b.y() ? a.y() < b.y() : a.z() < b.z();
  });
  GroundHeightEstimate best_estimate;
  best_estimate.cells = layers.size();
  if (layers.size() < std::max<std::size_t>(3, params.min_cells)) return std::nullopt;

  const double min_up = std::cos(params.max_tilt_deg * 3.14159265358979323846 / 180.0);
  struct Found {
    double height;  // the plane's z at the foot (x = y = 0), negative below the sensor
    std::size_t cells;
  };
  std::vector<Found> planes;
  std::vector<bool> taken(layers.size(), false);
  detail::SplitMix64 rng(0x9E0D);
  for (int k = 0; k < params.max_planes; ++k) {
    std::vector<std::size_t> free;
    for (std::size_t i = 0; i < layers.size(); ++i) {
      if (!taken[i]) free.push_back(i);
    }
    if (free.size() < 3) break;
    // The plane n . p = c with the most inliers among the draws.
    Eigen::Vector3d best_n = Eigen::Vector3d::UnitZ();
    double best_c = 0.0;
    std::size_t best_count = 0;
    for (int it = 0; it < params.iterations; ++it) {
      const std::size_t a = free[rng.below(free.size())], b = free[rng.below(free.size())],
                        c = free[rng.below(free.size())];
      if (a == b || b == c || a == c) continue;
      Eigen::Vector3d n = (layers[b] - layers[a]).cross(layers[c] - layers[a]);
      if (n.norm() < 1e-9) continue;
      n.normalize();
      if (n.z() < 0.0) n = -n;
      if (n.z() < min_up) continue;
      const double offset = n.dot(layers[a]);
      std::size_t count = 0;
      for (const std::size_t i : free) count += std::abs(n.dot(layers[i]) - offset) <= params.inlier_distance;
      if (count > best_count) best_count = count, best_n = n, best_c = offset;
    }
    if (best_count < params.min_cells) break;
    // Least squares z = a x + b y + h on the inliers, twice.
    double height = best_c / best_n.z();
    Eigen::Vector3d slope(-best_n.x() / best_n.z(), -best_n.y() / best_n.z(), height);  // z = sx x + sy y + h
    std::vector<std::size_t> inliers;
    for (int pass = 0; pass < 2; ++pass) {
      inliers.clear();
      const Eigen::Vector3d normal = Eigen::Vector3d(-slope.x(), -slope.y(), 1.0).normalized();
      for (const std::size_t i : free) {
        const double off = (layers[i].z() - slope.x() * layers[i].x() - slope.y() * layers[i].y() - slope.z()) * normal.z();
        if (std::abs(off) <= params.inlier_distance) inliers.push_back(i);
      }
      if (inliers.size() < 3) break;
      Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
      Eigen::Vector3d atb = Eigen::Vector3d::Zero();
      for (const std::size_t i : inliers) {
        const Eigen::Vector3d row(layers[i].x(), layers[i].y(), 1.0);
        ata += row * row.transpose();
        atb += row * layers[i].z();
      }
      const Eigen::Vector3d solved = ata.ldlt().solve(atb);
      if (!solved.allFinite()) break;
      slope = solved;
    }
    for (const std::size_t i : inliers) taken[i] = true;
    if (inliers.size() < params.min_cells) break;
    planes.push_back(Found{slope.z(), inliers.size()});
  }
  if (planes.empty()) return std::nullopt;
  std::size_t largest = 0;
  for (const Found& f : planes) largest = std::max(largest, f.cells);
  const Found* ground = nullptr;
  for (const Found& f : planes) {
    if (4 * f.cells < largest) continue;
    if (!ground || f.height < ground->height) ground = &f;
  }
  best_estimate.height = -ground->height;
  best_estimate.plane_cells = ground->cells;
  return best_estimate;
}

}  // namespace streamclust
