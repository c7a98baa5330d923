// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The sensor's mount from its own points: the roll and pitch (yaw 0) that
/// make the ground plane horizontal, and the sensor's height above it, for a
/// sensor given neither poses nor a mount. A deterministic RANSAC search for
/// near-horizontal planes, and what stands on them to tell floor from
/// ceiling.
///
/// The rule.
/// 1. Planes. Up to `max_planes` planes are extracted one after the other
///    (each search sees only the points no earlier plane took): each is the
///    3-point hypothesis with the most inliers (distance <= inlier_distance)
///    among those whose normal lies within `max_tilt_deg` of the sensor's z
///    axis, **either sign**, refined twice by a least-squares fit to its
///    inliers. A plane is *large* when it holds at least
///    `min_plane_fraction` of the points; the search stops at the first that
///    is not. The first (largest) fixes the axis; its side of the sensor is
///    side A, the other side B; on each side the nearest large plane is the
///    candidate.
/// 2. The plane across. Without a large plane on side B, the farthest plane
///    parallel to A's on side B is searched in all the points (a floor seen
///    at grazing angles holds a thousandth of them): a pair of 1 cm bins
///    along the axis with at least max(20, points / 2000) points, twice the
///    density 3-15 cm nearer the sensor, and at least 4 times the points
///    beyond it (a floor or a ceiling bounds what is seen), showing in at
///    least a twentieth as many 0.5 m cells as plane A.
/// 3. Floor or ceiling. Objects stand on the floor and hang from nothing.
///    A point *touches* a plane when it lies 2 inlier_distance to
///    `contact_band` m off it, the plane goes on at least 1 m farther out
///    in its 2-degree sector (a floor continues behind what stands on it;
///    a wall ends it) and no point of its 0.5 m cell is that near the other
///    plane (a pillar touches both). A touching cell that also holds points
///    up to 1 m past the sensor's level (short of the other plane) is a
///    *column*: a pillar, a trunk, anything taller than the sensor's
///    height; it may stand on either plane.
///    With planes on both sides, the ground is the one touched in at least
///    `contact_ratio` times as many cells per cell showing it as the other,
///    and in 2 cells more at least; when neither is, the same test on the
///    touches but the columns.
///    With one plane (the *standing* cells hold points up to 2 m off it
///    where it goes on behind them): fewer than 15 standing cells are no
///    evidence against it (outdoors, the ground): found. Else it is the
///    ground when at least `standing_fraction` of the standing cells touch
///    it and not all of them are columns; a ceiling when fewer do and at
///    most `ceiling_fraction` of the standing cells but the columns touch
///    it: status `floor_out_of_view` (pillars alone reach a ceiling; the
///    floor beyond the sensor's lowest rays, its height unknown).
///    Otherwise the status is `ambiguous`.
///    Up is the ground's normal pointing towards the sensor (away from the
///    ceiling with the floor out of view): an upside-down sensor (roll 180)
///    finds roll 180, whichever plane is nearer.
///
/// The floor out of view: a level Mid-360 (rays from -7 deg) 1.2 or 1.5 m
/// up in a 20 x 12 m room meets the floor 9.8 or 12 m out, at or beyond the
/// walls: one plane, the ceiling, with pillars alone touching it. Its
/// normal gives roll and pitch; the sensor's height cannot be measured:
/// `floor_out_of_view`.
///
/// Failure cases (the estimate is then wrong, ambiguous or nullopt):
/// - a lone plane that about as many standing cells touch as not, columns
///   aside (tables on a floor seen from 1.2 m, their tops not touching):
///   ambiguous;
/// - mirror-symmetric evidence (two parallel planes, nothing standing on
///   either or as much on both): ambiguous;
/// - the sensor is tilted more than `max_tilt_deg`: the ground is no
///   candidate, and a wall then within max_tilt_deg of the z axis is taken
///   for it or for a ceiling (raising max_tilt_deg admits walls, and a wall
///   nearer than the ground wins);
/// - a large horizontal surface nearer than the ground on its side (a
///   platform, a big table top) is taken for the ground (its tilt is
///   usually the ground's);
/// - sloped ground is made horizontal: the mount then holds the slope; on
///   rolling terrain the plane is a fit to part of it;
/// - no plane holds min_plane_fraction of the points: nullopt. A plane
///   holding a share w of the points is found by `iterations` hypotheses
///   with probability 1 - (1 - w^3)^iterations (w = 0.2: 99.99 % at 2000).
///
/// Cost: O(iterations x max_points x max_planes) point-plane distances
/// (about 10 ms for the defaults) plus three passes over all the points
/// (the plane across and the contacts, a hash map of the occupied cells);
/// deterministic for a given input and seed (own generator, no std::
/// distributions).
///
/// \code
/// std::vector<Eigen::Vector3f> first_window = ...;     // sensor frame [m]
/// const auto ground = streamclust::estimate_ground(first_window);
/// streamclust::ObjectsSetup setup;                     // objects_presets.hpp
/// if (ground && ground->status != streamclust::GroundStatus::ambiguous) setup.mount = ground->mount;
/// if (ground && ground->status == streamclust::GroundStatus::found) {
///   setup.sensor_height = static_cast<float>(ground->height);  // unknown (0) with the floor out of view
/// }
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
#include <tuple>
#include <unordered_map>
#include <utility>
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
  double contact_band = 0.5;       ///< [m] points up to this far off a plane touch it, (2 inlier_distance, 10]
  double contact_ratio = 2.0;      ///< planes on both sides: the ground's touches per cell over the other's, >= 1
  double standing_fraction = 0.5;  ///< one plane: share of what stands near it that touches it, (0, 1]
  double ceiling_fraction = 0.15;  ///< one plane: most share of what stands near it, columns aside, touching a
                                   ///< ceiling, [0, standing_fraction)
};

/// What estimate_ground could tell.
enum class GroundStatus : std::uint8_t {
  found,      ///< the ground plane, told from a ceiling by what stands on it
  ambiguous,  ///< planes, but nothing tells which is below: the fields hold plane A as a guess; give the mount
  /// One plane, a ceiling (what stands near it does not touch it, columns
  /// aside); the floor is out of view: the mount (up away from the ceiling)
  /// and the ceiling's distance are known, the sensor's height is not (0).
  floor_out_of_view,
};

/// The ground found by estimate_ground.
struct GroundEstimate {
  Pose mount;                                        ///< roll and pitch, yaw 0, no translation: up -> +z
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();     ///< the ground's unit normal towards the sensor, sensor frame
  double height = 0.0;  ///< [m] the sensor's distance from the ground plane (0: floor_out_of_view, unknown)
  double roll_deg = 0.0, pitch_deg = 0.0;            ///< [deg] of the mount (mount_from_roll_pitch_yaw_deg's)
  std::size_t inliers = 0;  ///< points on the ground plane among those used (0: the plane across, rule 2, or none)
  std::size_t points_used = 0;                       ///< finite points used
  GroundStatus status = GroundStatus::found;         ///< found, ambiguous (the fields a guess) or floor_out_of_view
  double opposite_distance = 0.0;  ///< [m] the sensor's distance from the plane across it (a ceiling), 0: none seen
  double contact = 0.0;  ///< the evidence for this plane (touches per cell; one plane: share touching; 0: not seen)
  double opposite_contact = 0.0;   ///< the same for the plane across (0: none; a lone ceiling: columns aside)
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
  if (!(p.contact_band > 2.0 * p.inlier_distance && p.contact_band <= 10.0))
    fail("contact_band", p.contact_band, "(2 inlier_distance, 10] m");
  if (!(p.contact_ratio >= 1.0 && p.contact_ratio <= 1e6)) fail("contact_ratio", p.contact_ratio, "[1, 1e6]");
  if (!(p.standing_fraction > 0.0 && p.standing_fraction <= 1.0))
    fail("standing_fraction", p.standing_fraction, "(0, 1]");
  if (!(p.ceiling_fraction >= 0.0 && p.ceiling_fraction < p.standing_fraction))
    fail("ceiling_fraction", p.ceiling_fraction, "[0, standing_fraction)");
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

namespace detail {

/// A near-horizontal plane found by the RANSAC search: the normal towards
/// the sensor (n . 0 + d = d > 0: d is the sensor's distance from it).
struct FoundPlane {
  Plane plane;
  std::size_t inliers = 0;
};

/// Up to `params.max_planes` large near-horizontal planes of `points`, in the
/// order found (each search sees the points no earlier plane took). See the
/// file comment. O(iterations x points x max_planes).
inline std::vector<FoundPlane> horizontal_planes(const std::vector<Eigen::Vector3d>& points,
                                                 const MountEstimateParams& params) {
  const std::size_t total = points.size();
  const auto large = static_cast<std::size_t>(std::ceil(params.min_plane_fraction * static_cast<double>(total)));
  const double min_abs_nz = std::cos(params.max_tilt_deg * 3.14159265358979323846 / 180.0);
  std::vector<std::size_t> remaining(total);
  for (std::size_t i = 0; i < total; ++i) remaining[i] = i;
  std::vector<std::size_t> best_inliers, kept;
  SplitMix64 rng{params.seed};
  std::vector<FoundPlane> found;
  for (std::size_t plane_no = 0; plane_no < params.max_planes; ++plane_no) {
    const std::size_t m = remaining.size();
    if (m < 3 || m < large) break;
    // RANSAC over near-horizontal 3-point hypotheses.
    std::size_t best = 0;
    Plane best_plane;
    for (std::size_t it = 0; it < params.iterations; ++it) {
      const std::size_t a = rng.below(m), b = rng.below(m), c = rng.below(m);
      if (a == b || b == c || a == c) continue;
      const Eigen::Vector3d& pa = points[remaining[a]];
      const Eigen::Vector3d n = (points[remaining[b]] - pa).cross(points[remaining[c]] - pa);
      const double len = n.norm();
      if (!(len > 1e-12)) continue;
      Plane h{n / len, 0.0};
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
    plane_inliers(points, remaining, best_plane, params.inlier_distance, best_inliers);
    Plane plane = best_plane;
    for (int round = 0; round < 2 && best_inliers.size() >= 3; ++round) {
      plane = fit_plane(points, best_inliers);
      plane_inliers(points, remaining, plane, params.inlier_distance, best_inliers);
    }
    if (best_inliers.size() < 3 || best_inliers.size() < large || std::abs(plane.n.z()) < min_abs_nz) break;
    if (plane.d < 0.0) {  // the normal towards the sensor (the origin): n . 0 + d > 0
      plane.n = -plane.n;
      plane.d = -plane.d;
    }
    found.push_back(FoundPlane{plane, best_inliers.size()});
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
  return found;
}

/// The plane across found by farthest_parallel_plane: the sensor's distance
/// from it [m] (0: none) and its points.
struct PlanePeak {
  double distance = 0.0;
  std::size_t points = 0;
};

/// The farthest plane perpendicular to `up` on the side `up` points to,
/// among all of `points` (rule 2 of the file comment): the farthest pair of
/// `bin` m bins of `up . p` (0 to `max_distance`) holding at least
/// `min_points`, twice the points of the mean pair 3-15 cm nearer the
/// sensor, and at least 4 times the points beyond it. Its distance is the mean
/// over its points. O(points + max_distance / bin).
inline PlanePeak farthest_parallel_plane(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3d& up,
                                         double bin, double max_distance, std::size_t min_points) {
  const auto bins = static_cast<std::size_t>(std::ceil(max_distance / bin)) + 2;
  std::vector<std::size_t> hist(bins, 0);
  for (const Eigen::Vector3f& p : points) {
    if (!p.allFinite()) continue;
    const double s = up.dot(p.cast<double>());
    if (s > 0.0 && s < max_distance) ++hist[static_cast<std::size_t>(s / bin)];
  }
  const auto near_lo = static_cast<std::size_t>(std::ceil(0.03 / bin));
  const auto near_hi = static_cast<std::size_t>(0.15 / bin);
  std::size_t beyond = 0;  // points in the bins past k + 1
  for (std::size_t k = bins - 1; k-- > 1;) {  // farthest first; bin 0 (at the sensor) is no plane
    const std::size_t here = hist[k] + hist[k + 1];  // a plane may straddle two bins
    if (here >= min_points && 4 * beyond <= here) {
      double around = 0.0;  // the density on the sensor's side of it, 3-15 cm nearer
      std::size_t counted = 0;
      for (std::size_t off = near_lo; off <= near_hi && off <= k; ++off) around += static_cast<double>(hist[k - off]), ++counted;
      const double mean_around = counted > 0 ? around / static_cast<double>(counted) : 0.0;
      if (static_cast<double>(here) >= 2.0 * 2.0 * mean_around) {
        double sum = 0.0;
        std::size_t n = 0;
        const double lo = static_cast<double>(k) * bin, hi = lo + 2.0 * bin;
        for (const Eigen::Vector3f& p : points) {
          if (!p.allFinite()) continue;
          const double s = up.dot(p.cast<double>());
          if (s >= lo && s < hi) sum += s, ++n;
        }
        if (n > 0) return PlanePeak{sum / static_cast<double>(n), n};
      }
    }
    beyond += hist[k + 1];
  }
  return PlanePeak{};
}

/// What stands on plane A (at distance `distance_a` along -axis) and plane B
/// (at `distance_b` along +axis; 0: none), rule 3 of the file comment, in
/// cells of `cell` m across the axis. Per plane: cells showing it, cells
/// touching it, cells holding points 2 tolerance to `reach` m off it
/// where it goes on behind them (`standing`), and the touching cells that
/// also hold points 2 tolerance to 1 m past the sensor's level, away from
/// the plane and short of the other (`columns`: a pillar, a trunk, a person
/// taller than the sensor's height; what reaches past the sensor may stand
/// on either side).
struct PlaneContacts {
  std::size_t shows = 0, touches = 0, standing = 0, columns = 0;
  /// Touching cells per cell showing the plane.
  double per_cell() const { return per_cell(touches); }
  /// `cells` per cell showing the plane.
  double per_cell(std::size_t cells) const {
    return shows > 0 ? static_cast<double>(cells) / static_cast<double>(shows) : 0.0;
  }
  /// Touching cells but the columns: what touches the plane and ends before the sensor's level.
  std::size_t low_touches() const { return touches - columns; }
  /// Share of the standing cells that touch the plane.
  double standing_share() const {
    return standing > 0 ? static_cast<double>(touches) / static_cast<double>(standing) : 0.0;
  }
};

/// Rule 3's counts for planes A and B from all of `points`. O(points)
/// with a hash map of the occupied cells.
inline std::pair<PlaneContacts, PlaneContacts> plane_contacts(const std::vector<Eigen::Vector3f>& points,
                                                              const Eigen::Vector3d& axis, double distance_a,
                                                              double distance_b, double tolerance, double band) {
  constexpr double kCell = 0.5;    // [m]
  constexpr double kBeyond = 1.0;  // [m] the plane goes on at least this much farther out
  constexpr double kReach = 2.0;   // [m] what stands near a plane: up to this far off it
  constexpr double kPast = 1.0;    // [m] a column's points past the sensor's level: up to this far
  constexpr int kSectors = 180;    // 2 deg each
  constexpr double kPi = 3.14159265358979323846;
  const Eigen::Vector3d e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  const double offset[2] = {distance_a, distance_b};  // off plane k (>= 0 on the sensor's side): sign_k s + offset_k
  const double sign[2] = {1.0, -1.0};
  const int planes = distance_b > 0.0 ? 2 : 1;
  // Past the sensor's level, away from plane k: up to kPast m, short of the other plane.
  const double past_limit[2] = {planes == 2 ? std::min(kPast, distance_b - 2.0 * tolerance) : kPast,
                                std::min(kPast, distance_a - 2.0 * tolerance)};
  const auto sector = [&](double x, double y) {
    const int k = static_cast<int>(std::floor((std::atan2(y, x) + kPi) / (2.0 * kPi) * kSectors));
    return std::min(std::max(k, 0), kSectors - 1);
  };
  // Pass 1: how far out each plane shows in each sector [m].
  std::vector<double> reach[2] = {std::vector<double>(kSectors, -1.0), std::vector<double>(kSectors, -1.0)};
  for (const Eigen::Vector3f& pf : points) {
    if (!pf.allFinite()) continue;
    const Eigen::Vector3d p = pf.cast<double>();
    const double s = axis.dot(p), x = e1.dot(p), y = e2.dot(p);
    for (int k = 0; k < planes; ++k) {
      if (std::abs(sign[k] * s + offset[k]) <= tolerance) {
        double& r = reach[k][static_cast<std::size_t>(sector(x, y))];
        r = std::max(r, std::hypot(x, y));
      }
    }
  }
  // Pass 2: per cell, per plane: shows, near (within band), touches (near, plane goes on), standing, past the
  // sensor's level.
  enum : std::uint8_t { kShows = 1, kNear = 2, kTouches = 4, kStanding = 8, kPastSensor = 16 };
  std::unordered_map<std::uint64_t, std::uint16_t> cells;  // plane A's flags in bits 0-4, B's in 8-12
  for (const Eigen::Vector3f& pf : points) {
    if (!pf.allFinite()) continue;
    const Eigen::Vector3d p = pf.cast<double>();
    const double s = axis.dot(p), x = e1.dot(p), y = e2.dot(p);
    std::uint16_t flags = 0;
    for (int k = 0; k < planes; ++k) {
      const double off = sign[k] * s + offset[k];  // >= 0 on the sensor's side
      std::uint8_t f = sign[k] * s > 2.0 * tolerance && sign[k] * s <= past_limit[k] ? kPastSensor : 0;
      if (std::abs(off) <= tolerance) {
        f |= kShows;
      } else if (off > 2.0 * tolerance && off <= kReach &&
                 reach[k][static_cast<std::size_t>(sector(x, y))] >= std::hypot(x, y) + kBeyond) {
        f |= off <= band ? (kNear | kTouches | kStanding) : kStanding;
      } else if (off > 2.0 * tolerance && off <= band) {
        f |= kNear;  // near, the plane not going on behind: it still marks a pillar's cell
      }
      flags = static_cast<std::uint16_t>(flags | (f << (8 * k)));
    }
    if (flags == 0) continue;
    // A cell index must fit int64: points beyond 1e9 m (no scan's) have none.
    if (!(std::abs(x) < 1e9 && std::abs(y) < 1e9)) continue;
    const auto i = static_cast<std::int64_t>(std::floor(x / kCell)), j = static_cast<std::int64_t>(std::floor(y / kCell));
    cells[(static_cast<std::uint64_t>(i) << 32) ^ (static_cast<std::uint64_t>(j) & 0xffffffffu)] |= flags;
  }
  PlaneContacts out[2];
  for (const auto& entry : cells) {
    const std::uint8_t flags[2] = {static_cast<std::uint8_t>(entry.second & 0xffu),
                                   static_cast<std::uint8_t>(entry.second >> 8)};
    const bool near_both = (flags[0] & kNear) != 0 && (flags[1] & kNear) != 0;  // a pillar, a wall
    for (int k = 0; k < 2; ++k) {
      out[k].shows += (flags[k] & kShows) != 0;
      if (near_both) continue;
      out[k].touches += (flags[k] & kTouches) != 0;
      out[k].standing += (flags[k] & kStanding) != 0;
      out[k].columns += (flags[k] & kTouches) != 0 && (flags[k] & kPastSensor) != 0;
    }
  }
  return {out[0], out[1]};
}

}  // namespace detail

/// The ground plane of `sensor_points` (sensor frame [m]; non-finite points
/// are skipped) by the rule of this header, and the mount that makes it
/// horizontal; nullopt when fewer than 3 finite points or no large
/// near-horizontal plane; status `ambiguous` when what stands on the planes
/// does not tell floor from ceiling. Throws std::invalid_argument for bad
/// params.
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
  // 1. Planes; the nearest large one on each side of the sensor.
  const std::vector<detail::FoundPlane> planes = detail::horizontal_planes(points, params);
  if (planes.empty()) return std::nullopt;
  const Eigen::Vector3d axis = planes.front().plane.n;  // from side A towards the sensor
  std::optional<detail::FoundPlane> side_a, side_b;
  for (const detail::FoundPlane& f : planes) {
    std::optional<detail::FoundPlane>& side = f.plane.n.dot(axis) > 0.0 ? side_a : side_b;
    if (!side || f.plane.d < side->plane.d) side = f;
  }
  // 2. The plane across, when no large one: a peak along the axis.
  double distance_b = side_b ? side_b->plane.d : 0.0;
  if (!side_b) {
    distance_b = detail::farthest_parallel_plane(sensor_points, axis, 0.01, 50.0,
                                                 std::max<std::size_t>(20, finite / 2000)).distance;
  }
  // 3. What stands on them.
  auto [on_a, on_b] = detail::plane_contacts(sensor_points, axis, side_a->plane.d, distance_b,
                                             params.inlier_distance, params.contact_band);
  if (!side_b && distance_b > 0.0 && 20 * on_b.shows < on_a.shows) {  // too small to be a floor or ceiling
    distance_b = 0.0;
    std::tie(on_a, on_b) = detail::plane_contacts(sensor_points, axis, side_a->plane.d, 0.0, params.inlier_distance,
                                                  params.contact_band);
  }
  constexpr std::size_t kMinTouches = 2;         // the ground's lead in touching cells, at least
  constexpr std::size_t kMinStandingCells = 15;  // fewer are no evidence against a lone plane
  bool a_is_ground = true;
  GroundStatus status = GroundStatus::ambiguous;
  double contact = 0.0, opposite_contact = 0.0;
  if (distance_b > 0.0) {
    // The plane touched more wins; when neither is, the touches but the columns (which may stand on either).
    const auto decide = [&](const detail::PlaneContacts& plane_a, std::size_t touches_a,
                            const detail::PlaneContacts& plane_b, std::size_t touches_b) {
      const double a = plane_a.per_cell(touches_a), b = plane_b.per_cell(touches_b);
      if (touches_a >= touches_b + kMinTouches && a >= params.contact_ratio * b) {
        status = GroundStatus::found;
      } else if (touches_b >= touches_a + kMinTouches && b >= params.contact_ratio * a) {
        status = GroundStatus::found;
        a_is_ground = false;
      }
    };
    decide(on_a, on_a.touches, on_b, on_b.touches);
    if (status == GroundStatus::ambiguous) decide(on_a, on_a.low_touches(), on_b, on_b.low_touches());
    contact = (a_is_ground ? on_a : on_b).per_cell();
    opposite_contact = (a_is_ground ? on_b : on_a).per_cell();
  } else {
    // Columns (touching and reaching past the sensor's level) may stand on either side; the other touches
    // are the evidence of a floor.
    contact = on_a.standing_share();
    const std::size_t low_touches = on_a.low_touches(), low_standing = on_a.standing - on_a.columns;
    const bool few_low_touches = static_cast<double>(low_touches) <=
                                 params.ceiling_fraction * static_cast<double>(low_standing);
    if (on_a.standing < kMinStandingCells || (contact >= params.standing_fraction && low_touches > 0)) {
      status = GroundStatus::found;
    } else if (contact < params.standing_fraction && few_low_touches) {
      status = GroundStatus::floor_out_of_view;
      a_is_ground = false;
      contact = 0.0;
      opposite_contact = low_standing > 0 ? static_cast<double>(low_touches) / static_cast<double>(low_standing) : 0.0;
    }
  }
  GroundEstimate g;
  g.status = status;
  g.up = a_is_ground ? side_a->plane.n : side_b ? side_b->plane.n : Eigen::Vector3d(-axis);
  g.height = a_is_ground ? side_a->plane.d : distance_b;  // 0 with the floor out of view
  g.opposite_distance = a_is_ground ? distance_b : side_a->plane.d;
  g.inliers = a_is_ground ? side_a->inliers : (side_b ? side_b->inliers : 0);
  g.points_used = points.size();
  g.contact = contact;
  g.opposite_contact = opposite_contact;
  // up = R^T z for R = Ry(pitch) Rx(roll): up = (-sin pitch, sin roll cos pitch, cos roll cos pitch).
  constexpr double deg = 180.0 / 3.14159265358979323846;
  g.roll_deg = std::atan2(g.up.y(), g.up.z()) * deg;
  g.pitch_deg = std::atan2(-g.up.x(), std::hypot(g.up.y(), g.up.z())) * deg;
  g.mount = mount_from_roll_pitch_yaw_deg(g.roll_deg, g.pitch_deg, 0.0);
  return g;
}

/// The mount (roll and pitch, yaw 0, no translation) that makes the ground
/// of `sensor_points` horizontal: `estimate_ground(...)->mount` when the
/// ground is found or the floor is out of view (a ceiling tells which way is
/// up), else nullopt (also when the estimate is ambiguous).
inline std::optional<Pose> estimate_mount(const std::vector<Eigen::Vector3f>& sensor_points,
                                          const MountEstimateParams& params = {}) {
  const std::optional<GroundEstimate> ground = estimate_ground(sensor_points, params);
  if (!ground || ground->status == GroundStatus::ambiguous) return std::nullopt;
  return ground->mount;
}

}  // namespace streamclust
