// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The peers of `streamclust evaluate --objects`: exact fixed-radius
/// Euclidean single linkage (what PCL's EuclideanClusterExtraction computes)
/// on a hash grid, and RANSAC removal of the dominant plane (the classic
/// frame pipeline's ground stage). Both work on one window of points.

#include <streamclust/detail/union_find.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace streamclust::cli {

/// Connected components of the graph joining every two points at most
/// `radius` apart (Euclidean single linkage, exact).
///
/// Method: cells of edge radius / 2 (a cell's diagonal, 0.87 radius, is
/// below the radius, so the points of one cell are one component from the
/// start); two cells up to two apart on every axis are joined when any pair
/// of their points is within the radius (the search stops at the first
/// pair, and skips cell pairs already joined). Union-find over the cells.
///
/// Cost: O(n log n) for the sort, plus per occupied cell 62 neighbour
/// lookups and, for each neighbour not yet joined, up to |a| |b| distance
/// tests. Memory O(n). Buffers are reused between calls. Not thread-safe.
class EuclideanClustering {
 public:
  /// Throws std::invalid_argument unless radius is finite and in (0, 100] m.
  explicit EuclideanClustering(float radius) : radius_(radius) {
    if (!(radius > 0.0f) || !(radius <= 100.0f)) {
      throw std::invalid_argument("EuclideanClustering: radius = " + std::to_string(radius) +
                                  " is invalid; allowed: (0, 100] m");
    }
    inverse_cell_ = 2.0f / radius;
  }

  /// Labels `points`: a component number per point (0, 1, ... in order of
  /// each component's first point). Non-finite points get -1 and join
  /// nothing. The reference stays valid until the next call.
  const std::vector<std::int64_t>& cluster(const std::vector<Eigen::Vector3f>& points) {
    const std::size_t n = points.size();
    labels_.assign(n, -1);
    order_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      if (points[i].allFinite()) order_.push_back({key_of(points[i]), static_cast<std::uint32_t>(i)});
    }
    std::sort(order_.begin(), order_.end());
    // Cells: runs of one key in order_.
    cell_begin_.clear();
    cell_of_key_.clear();
    cell_of_key_.reserve(order_.size());
    for (std::size_t k = 0; k < order_.size(); ++k) {
      if (k == 0 || order_[k].first != order_[k - 1].first) {
        cell_of_key_.emplace(order_[k].first, static_cast<std::uint32_t>(cell_begin_.size()));
        cell_begin_.push_back(static_cast<std::uint32_t>(k));
      }
    }
    const auto cells = static_cast<std::uint32_t>(cell_begin_.size());
    cell_begin_.push_back(static_cast<std::uint32_t>(order_.size()));
    sets_.reset(cells);
    const float r2 = radius_ * radius_;
    for (std::uint32_t a = 0; a < cells; ++a) {
      const std::uint64_t key = order_[cell_begin_[a]].first;
      const std::int64_t ax = unpack(key, 42), ay = unpack(key, 21), az = unpack(key, 0);
      for (int dx = 0; dx <= 2; ++dx) {
        for (int dy = -2; dy <= 2; ++dy) {
          for (int dz = -2; dz <= 2; ++dz) {
            // The 62 neighbours after this cell in (dx, dy, dz) order.
            if (dx == 0 && (dy < 0 || (dy == 0 && dz <= 0))) continue;
            const auto it = cell_of_key_.find(pack(ax + dx, ay + dy, az + dz));
            if (it == cell_of_key_.end()) continue;
            const std::uint32_t b = it->second;
            if (sets_.find(a) == sets_.find(b)) continue;
            if (any_pair_within(a, b, points, r2)) sets_.unite(a, b);
          }
        }
      }
    }
    // Number the components in order of their first point.
    number_.assign(cells, -1);
    std::int64_t next = 0;
    for (std::uint32_t c = 0; c < cells; ++c) {
      for (std::uint32_t k = cell_begin_[c]; k < cell_begin_[c + 1]; ++k) labels_[order_[k].second] = c;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (labels_[i] < 0) continue;
      const std::uint32_t root = sets_.find(static_cast<std::uint32_t>(labels_[i]));
      if (number_[root] < 0) number_[root] = next++;
      labels_[i] = number_[root];
    }
    return labels_;
  }

  float radius() const { return radius_; }

 private:
  static constexpr std::int64_t kOffset = std::int64_t{1} << 20;  ///< cell coordinates in [-2^20, 2^20)
  static constexpr std::uint64_t kMask = (std::uint64_t{1} << 21) - 1;

  static std::uint64_t pack(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x + kOffset) & kMask) << 42 | (static_cast<std::uint64_t>(y + kOffset) & kMask) << 21 |
           (static_cast<std::uint64_t>(z + kOffset) & kMask);
  }
  static std::int64_t unpack(std::uint64_t key, int shift) {
    return static_cast<std::int64_t>((key >> shift) & kMask) - kOffset;
  }
  /// The cell of a point; coordinates beyond +-2^20 cells (+-157 km at
  /// 0.3 m) are clamped: such points share the border cells.
  std::uint64_t key_of(const Eigen::Vector3f& p) const {
    const auto cell = [this](float v) {
      const double c = std::floor(static_cast<double>(v) * static_cast<double>(inverse_cell_));
      const double limit = static_cast<double>(kOffset - 3);
      return static_cast<std::int64_t>(std::clamp(c, -limit, limit));
    };
    return pack(cell(p.x()), cell(p.y()), cell(p.z()));
  }

  bool any_pair_within(std::uint32_t a, std::uint32_t b, const std::vector<Eigen::Vector3f>& points, float r2) const {
    for (std::uint32_t i = cell_begin_[a]; i < cell_begin_[a + 1]; ++i) {
      const Eigen::Vector3f& p = points[order_[i].second];
      for (std::uint32_t j = cell_begin_[b]; j < cell_begin_[b + 1]; ++j) {
        if ((points[order_[j].second] - p).squaredNorm() <= r2) return true;
      }
    }
    return false;
  }

  float radius_;
  float inverse_cell_;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order_;  ///< (cell key, point), sorted
  std::vector<std::uint32_t> cell_begin_;                         ///< first entry of each cell in order_, then the end
  std::unordered_map<std::uint64_t, std::uint32_t> cell_of_key_;
  ::streamclust::detail::UnionFind sets_;
  std::vector<std::int64_t> number_;
  std::vector<std::int64_t> labels_;
};

/// A plane n . p + d = 0 (n unit) and the points within the distance of it.
struct PlaneFit {
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();
  float offset = 0.0f;      ///< d [m]
  std::size_t inliers = 0;  ///< points within the fit's distance
  bool found = false;       ///< false: fewer than 3 points, or every draw degenerate
};

/// RANSAC for the dominant plane (PCL's SACMODEL_PLANE with plain RANSAC,
/// no refinement): `iterations` draws of three distinct points (a generator
/// seeded with `seed`: the same input gives the same plane), each plane
/// scored by the points within `distance` of it; the first best is kept.
/// Draws of (nearly) collinear points are skipped. O(iterations n).
/// Throws std::invalid_argument for distance outside (0, 10] m or
/// iterations outside [1, 100000].
inline PlaneFit ransac_dominant_plane(const std::vector<Eigen::Vector3f>& points, float distance,
                                      std::size_t iterations, std::uint64_t seed) {
  if (!(distance > 0.0f) || !(distance <= 10.0f)) {
    throw std::invalid_argument("ransac_dominant_plane: distance = " + std::to_string(distance) +
                                " is invalid; allowed: (0, 10] m");
  }
  if (iterations < 1 || iterations > 100000) {
    throw std::invalid_argument("ransac_dominant_plane: iterations = " + std::to_string(iterations) +
                                " is invalid; allowed: [1, 100000]");
  }
  PlaneFit best;
  const std::size_t n = points.size();
  if (n < 3) return best;
  std::mt19937_64 rng(seed);  // raw draws only: the same sequence on every standard library
  for (std::size_t it = 0; it < iterations; ++it) {
    const std::size_t i = static_cast<std::size_t>(rng() % n);
    const std::size_t j = static_cast<std::size_t>(rng() % n);
    const std::size_t k = static_cast<std::size_t>(rng() % n);
    if (i == j || j == k || i == k) continue;
    const Eigen::Vector3f u = points[j] - points[i];
    const Eigen::Vector3f v = points[k] - points[i];
    Eigen::Vector3f normal = u.cross(v);
    const float norm = normal.norm();
    if (!(norm > 1e-6f * u.norm() * v.norm()) || !std::isfinite(norm)) continue;
    normal /= norm;
    const float offset = -normal.dot(points[i]);
    std::size_t inliers = 0;
    for (const Eigen::Vector3f& p : points) inliers += std::abs(normal.dot(p) + offset) <= distance ? 1u : 0u;
    if (!best.found || inliers > best.inliers) best = PlaneFit{normal, offset, inliers, true};
  }
  return best;
}

}  // namespace streamclust::cli
