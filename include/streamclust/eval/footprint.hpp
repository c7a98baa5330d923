// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Footprint: a rectangle in the ground plane turned by a yaw, with its
/// bird's-eye intersection over union (convex polygon clipping) and the
/// distance of a point to it. For the tracking metrics.

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace streamclust {
namespace eval {

/// A rectangle in the ground plane: centre, length along `yaw`, width across.
struct Footprint {
  Eigen::Vector2f center = Eigen::Vector2f::Zero();  ///< [m]
  float yaw = 0.0f;     ///< [rad] of the length axis
  float length = 0.0f;  ///< [m] >= 0
  float width = 0.0f;   ///< [m] >= 0

  float area() const { return length * width; }

  /// The corners, counter-clockwise.
  std::array<Eigen::Vector2f, 4> corners() const {
    const Eigen::Vector2f u(std::cos(yaw), std::sin(yaw)), v(-u.y(), u.x());
    const Eigen::Vector2f a = 0.5f * length * u, b = 0.5f * width * v;
    return {center - a - b, center + a - b, center + a + b, center - a + b};
  }

  /// The distance from `p` to the rectangle [m]: 0 inside.
  float distance_to(const Eigen::Vector2f& p) const {
    const Eigen::Vector2f d = p - center;
    const float c = std::cos(yaw), s = std::sin(yaw);
    const float along = std::max(std::abs(c * d.x() + s * d.y()) - 0.5f * length, 0.0f);
    const float across = std::max(std::abs(-s * d.x() + c * d.y()) - 0.5f * width, 0.0f);
    return std::hypot(along, across);
  }
};

namespace detail {

/// The part of the convex counter-clockwise polygon `poly` left of the
/// directed edge a -> b (Sutherland-Hodgman, one edge).
inline std::vector<Eigen::Vector2f> clip_left_of(const std::vector<Eigen::Vector2f>& poly, const Eigen::Vector2f& a,
                                                 const Eigen::Vector2f& b) {
  std::vector<Eigen::Vector2f> out;
  const Eigen::Vector2f e = b - a;
  const auto side = [&](const Eigen::Vector2f& p) { return e.x() * (p.y() - a.y()) - e.y() * (p.x() - a.x()); };
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2f& p = poly[i];
    const Eigen::Vector2f& q = poly[(i + 1) % poly.size()];
    const float sp = side(p), sq = side(q);
    if (sp >= 0.0f) out.push_back(p);
    if ((sp >= 0.0f) != (sq >= 0.0f)) out.push_back(p + (sp / (sp - sq)) * (q - p));
  }
  return out;
}

/// The area of a simple polygon (shoelace; positive counter-clockwise).
inline float polygon_area(const std::vector<Eigen::Vector2f>& poly) {
  double twice = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2f& p = poly[i];
    const Eigen::Vector2f& q = poly[(i + 1) % poly.size()];
    twice += static_cast<double>(p.x()) * q.y() - static_cast<double>(q.x()) * p.y();
  }
  return static_cast<float>(0.5 * twice);
}

}  // namespace detail

/// Bird's-eye intersection over union of two footprints, in [0, 1]; 0 when
/// either has no area. O(1).
inline float footprint_iou(const Footprint& a, const Footprint& b) {
  if (!(a.area() > 0.0f) || !(b.area() > 0.0f)) return 0.0f;
  const float reach = 0.5f * (std::hypot(a.length, a.width) + std::hypot(b.length, b.width));
  if ((a.center - b.center).norm() >= reach) return 0.0f;
  const std::array<Eigen::Vector2f, 4> ca = a.corners(), cb = b.corners();
  std::vector<Eigen::Vector2f> poly(ca.begin(), ca.end());
  for (std::size_t i = 0; i < 4 && !poly.empty(); ++i) poly = detail::clip_left_of(poly, cb[i], cb[(i + 1) % 4]);
  const float inter = poly.size() >= 3 ? std::max(detail::polygon_area(poly), 0.0f) : 0.0f;
  const float uni = a.area() + b.area() - inter;
  return uni > 0.0f ? std::clamp(inter / uni, 0.0f, 1.0f) : 0.0f;
}

}  // namespace eval
}  // namespace streamclust
