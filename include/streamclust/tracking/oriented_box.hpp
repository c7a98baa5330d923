// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// OrientedBox and fit_oriented_box: an object's box in the ground plane
/// (yaw about the vertical axis), fitted to its points by the L-shape
/// closeness criterion, which holds on partial views: one visible side, or
/// the two sides of a corner (Zhang et al., "Efficient L-Shape Fitting for
/// Vehicle Detection Using Laser Scanners", IV 2017).

#include <streamclust/detail/parameter_check.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {
namespace tracking {

/// How far a box can be trusted.
enum class BoxQuality {
  two_sides,   ///< two adjacent sides seen (an L): yaw and extent are the object's
  one_side,    ///< one side seen: yaw from it; the extent across it is what shows (a lower bound)
  scattered,   ///< no side stands out (vegetation, a blob): the yaw is weak
  few_points,  ///< fewer than BoxFitParams::min_points: the yaw is a guess
};

/// "two_sides", "one_side", "scattered" or "few_points".
inline const char* to_string(BoxQuality q) {
  switch (q) {
    case BoxQuality::two_sides: return "two_sides";
    case BoxQuality::one_side: return "one_side";
    case BoxQuality::scattered: return "scattered";
    case BoxQuality::few_points: return "few_points";
  }
  return "unknown";
}

/// A box standing on the ground plane: its centre, its extent along its
/// own axes and its heading. Frame: the points' (the world frame with poses
/// or a mount, z up).
struct OrientedBox {
  Eigen::Vector3f center = Eigen::Vector3f::Zero();  ///< [m]
  float length = 0.0f;  ///< [m] along the heading, >= width
  float width = 0.0f;   ///< [m] across it
  float height = 0.0f;  ///< [m] from its bottom (the local ground under the object, or its lowest point) to its top
  float yaw = 0.0f;     ///< [rad] heading of the long side from the x axis, in [-pi/2, pi/2)
  BoxQuality quality = BoxQuality::few_points;
  bool on_ground = false;  ///< the bottom is the ground under the object, not its lowest point
  std::size_t points = 0;  ///< points fitted

  /// Bottom of the box [m].
  float bottom() const { return center.z() - 0.5f * height; }
};

/// Settings of fit_oriented_box.
struct BoxFitParams {
  std::size_t search_points = 48;  ///< points the heading search looks at (an even sample), [8, 100000]
  float closeness_floor = 0.01f;   ///< [m] distance to a side below which points count alike, (0, 1]
  float side_band = 0.15f;         ///< [m] a point this close to a side supports it, (0, 5]
  float side_share = 0.25f;        ///< share of the points a seen side holds, (0, 1]
  std::size_t min_points = 10;     ///< fewer points: quality few_points, [1, 100000]
  float min_size = 0.05f;          ///< [m] smallest length, width and height reported, [0, 10]
  float max_foot_gap = 0.5f;       ///< [m] the ground this far below the lowest point is the box's bottom, [0, 10]

  /// Throws std::invalid_argument naming the first setting out of range.
  void validate() const {
    auto check = [](bool ok, const char* name, double value, const char* allowed) {
      streamclust::detail::require_parameter(ok, "BoxFitParams", name, value, allowed);
    };
    check(search_points >= 8 && search_points <= 100000, "search_points", static_cast<double>(search_points),
          "[8, 100000]");
    check(closeness_floor > 0.0f && closeness_floor <= 1.0f, "closeness_floor", closeness_floor, "(0, 1] m");
    check(side_band > 0.0f && side_band <= 5.0f, "side_band", side_band, "(0, 5] m");
    check(side_share > 0.0f && side_share <= 1.0f, "side_share", side_share, "(0, 1]");
    check(min_points >= 1 && min_points <= 100000, "min_points", static_cast<double>(min_points), "[1, 100000]");
    check(min_size >= 0.0f && min_size <= 10.0f, "min_size", min_size, "[0, 10] m");
    check(max_foot_gap >= 0.0f && max_foot_gap <= 10.0f, "max_foot_gap", max_foot_gap, "[0, 10] m");
  }
};

namespace detail {

/// The closeness score of heading `theta` [rad] over `xy`: each point
/// scores 1 / max(distance to the nearer side of the tightest box at that
/// heading, floor). High when the points hug two adjacent sides. O(n).
inline double closeness_score(const std::vector<Eigen::Vector2f>& xy, float theta, float floor) {
  const float c = std::cos(theta), s = std::sin(theta);
  float lo1 = std::numeric_limits<float>::max(), hi1 = -lo1, lo2 = lo1, hi2 = -lo1;
  for (const Eigen::Vector2f& p : xy) {
    const float a = c * p.x() + s * p.y(), b = c * p.y() - s * p.x();
    lo1 = std::min(lo1, a);
    hi1 = std::max(hi1, a);
    lo2 = std::min(lo2, b);
    hi2 = std::max(hi2, b);
  }
  const auto term = [&](const Eigen::Vector2f& p) {
    const float a = c * p.x() + s * p.y(), b = c * p.y() - s * p.x();
    const float d = std::min(std::min(hi1 - a, a - lo1), std::min(hi2 - b, b - lo2));
    return 1.0f / std::max(d, floor);
  };
  // Four independent sums: the divisions overlap instead of queueing on one
  // accumulator.
  float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const std::size_t n = xy.size(), quads = n / 4 * 4;
  for (std::size_t i = 0; i < quads; i += 4) {
    sum[0] += term(xy[i]);
    sum[1] += term(xy[i + 1]);
    sum[2] += term(xy[i + 2]);
    sum[3] += term(xy[i + 3]);
  }
  for (std::size_t i = quads; i < n; ++i) sum[0] += term(xy[i]);
  return static_cast<double>(sum[0] + sum[1]) + static_cast<double>(sum[2] + sum[3]);
}

/// The heading in [0, pi/2) with the best closeness score: 9 steps of
/// 10 deg, then 2 deg, 0.5 deg and 0.125 deg steps around the best (9 + 8 +
/// 6 + 6 = 29 scores). At each step the floor is at least what half the
/// step turns the farthest point by, so the coarse steps see a smoothed
/// score whose peak they cannot step over (at 0.02 m of noise the sharp
/// score's peak is 1 deg wide).
inline float best_heading(const std::vector<Eigen::Vector2f>& xy, float floor) {
  constexpr float kDeg = 0.017453292519943295f;
  constexpr float kQuarter = 1.5707963267948966f;
  float reach = 0.0f;
  for (const Eigen::Vector2f& p : xy) reach = std::max(reach, p.norm());
  float best = 0.0f;
  double best_score = -1.0;
  float level_floor = floor;
  const auto consider = [&](float theta) {
    theta = std::fmod(theta + kQuarter, kQuarter);  // the score has period pi/2
    const double score = closeness_score(xy, theta, level_floor);
    if (score > best_score) {
      best_score = score;
      best = theta;
    }
  };
  const auto floor_for = [&](float step_deg) { return std::max(floor, std::tan(0.5f * step_deg * kDeg) * reach); };
  level_floor = floor_for(10.0f);
  for (int i = 0; i < 9; ++i) consider(static_cast<float>(i) * 10.0f * kDeg);
  // Refinements: `half` steps of `step` on either side of the best so far.
  const auto refine = [&](float step_deg, int half) {
    const float centre = best;
    level_floor = floor_for(step_deg);
    best_score = closeness_score(xy, centre, level_floor);
    for (int i = -half; i <= half; ++i) {
      if (i != 0) consider(centre + static_cast<float>(i) * step_deg * kDeg);
    }
  };
  refine(2.0f, 4);
  refine(0.5f, 3);
  refine(0.125f, 3);
  return best;
}

}  // namespace detail

/// Scratch storage of fit_oriented_box, reused between calls (no
/// allocation once it has grown to the largest object).
struct BoxFitScratch {
  std::vector<Eigen::Vector2f> sample;
};

/// Fits a box to one object's points `xyz` (at least one; world frame, z
/// up). The heading maximises the closeness criterion over an even sample of
/// `search_points` of them (relative to their mean, so far objects keep
/// their precision); the extent along it and across it covers every point.
/// The bottom is `ground_z` (the local ground under the object) when it
/// lies within `max_foot_gap` of the lowest point (feet classed ground
/// belong to the object; the lower of the two), else the lowest point (an
/// overhang, a crown).
/// Quality: a side is seen when `side_share` of the sample lies within
/// `side_band` of it; two adjacent seen sides make two_sides.
/// O(n + 29 x search_points). Thread safety: none on `scratch`.
inline OrientedBox fit_oriented_box(const std::vector<Eigen::Vector3f>& xyz, std::optional<float> ground_z,
                                    const BoxFitParams& params, BoxFitScratch& scratch) {
  OrientedBox box;
  box.points = xyz.size();
  if (xyz.empty()) return box;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  float z_lo = std::numeric_limits<float>::max(), z_hi = -z_lo;
  for (const Eigen::Vector3f& p : xyz) {
    mean += p.cast<double>();
    z_lo = std::min(z_lo, p.z());
    z_hi = std::max(z_hi, p.z());
  }
  mean /= static_cast<double>(xyz.size());
  const Eigen::Vector2f origin = mean.head<2>().cast<float>();

  // Even sample for the heading search.
  scratch.sample.clear();
  const std::size_t n = xyz.size(), m = std::min(n, params.search_points);
  for (std::size_t i = 0; i < m; ++i) scratch.sample.push_back(xyz[i * n / m].head<2>() - origin);
  const float theta = n >= 2 ? detail::best_heading(scratch.sample, params.closeness_floor) : 0.0f;

  // Extent over every point along the heading (axis 1) and across it (axis 2).
  const float c = std::cos(theta), s = std::sin(theta);
  float lo1 = std::numeric_limits<float>::max(), hi1 = -lo1, lo2 = lo1, hi2 = -lo1;
  for (const Eigen::Vector3f& p : xyz) {
    const float x = p.x() - origin.x(), y = p.y() - origin.y();
    const float a = c * x + s * y, b = c * y - s * x;
    lo1 = std::min(lo1, a);
    hi1 = std::max(hi1, a);
    lo2 = std::min(lo2, b);
    hi2 = std::max(hi2, b);
  }
  // Sides seen: 0 lo1, 1 hi1, 2 lo2, 3 hi2.
  std::size_t near[4] = {0, 0, 0, 0};
  for (const Eigen::Vector2f& p : scratch.sample) {
    const float a = c * p.x() + s * p.y(), b = c * p.y() - s * p.x();
    near[0] += a - lo1 <= params.side_band;
    near[1] += hi1 - a <= params.side_band;
    near[2] += b - lo2 <= params.side_band;
    near[3] += hi2 - b <= params.side_band;
  }
  const auto seen = [&](int side) {
    return static_cast<float>(near[side]) >= params.side_share * static_cast<float>(scratch.sample.size());
  };
  const bool seen1 = seen(0) || seen(1), seen2 = seen(2) || seen(3);
  if (n < params.min_points) {
    box.quality = BoxQuality::few_points;
  } else if (seen1 && seen2) {
    box.quality = BoxQuality::two_sides;
  } else if (seen1 || seen2) {
    box.quality = BoxQuality::one_side;
  } else {
    box.quality = BoxQuality::scattered;
  }

  const float mid1 = 0.5f * (lo1 + hi1), mid2 = 0.5f * (lo2 + hi2);
  const Eigen::Vector2f centre_xy = origin + Eigen::Vector2f(c * mid1 - s * mid2, s * mid1 + c * mid2);
  float size1 = hi1 - lo1, size2 = hi2 - lo2, heading = theta;
  if (size2 > size1) {  // the long side leads
    std::swap(size1, size2);
    heading = theta + 1.5707963267948966f;
  }
  // Heading into [-pi/2, pi/2): a box's heading is a line, not a direction.
  constexpr float kPi = 3.14159265358979323846f;
  while (heading >= 0.5f * kPi) heading -= kPi;
  while (heading < -0.5f * kPi) heading += kPi;

  float bottom = z_lo;
  box.on_ground = ground_z && std::abs(z_lo - *ground_z) <= params.max_foot_gap;
  if (box.on_ground) bottom = std::min(*ground_z, z_lo);
  box.length = std::max(size1, params.min_size);
  box.width = std::max(size2, params.min_size);
  box.height = std::max(z_hi - bottom, params.min_size);
  box.center = Eigen::Vector3f(centre_xy.x(), centre_xy.y(), bottom + 0.5f * box.height);
  box.yaw = heading;
  return box;
}

}  // namespace tracking
}  // namespace streamclust
