// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Analytic ray intersection for the scan simulator's primitives: planes
/// (infinite or rectangular), boxes (axis-aligned or yaw-rotated), vertical
/// capped cylinders, spheres, axis-aligned ellipsoids and vertical capsules.
///
/// Every primitive has a free function
///
///     std::optional<float> intersect(const Shape&, const Eigen::Vector3f& origin,
///                                    const Eigen::Vector3f& direction);
///
/// returning the smallest `t > 0` with `origin + t * direction` on the
/// surface, or nothing. `t` is in units of `|direction|`: pass a unit
/// direction to get meters. Conventions, the same for every primitive:
///
/// - **Origin inside a solid** (box, cylinder, sphere, ellipsoid, capsule), or
///   on its surface: the shape is *ignored* (no hit), never the exit point. A
///   sensor can only be inside an object if ego-motion drives it through one;
///   it then sees through the object instead of producing a shell of bogus
///   points at a few centimeters.
/// - Planes are two-sided (hit from either side). A ray parallel to a plane,
///   or lying in it, does not hit it.
/// - A ray parallel to a box face or a cylinder cap is handled explicitly
///   (no division by zero): it hits if it travels inside that slab.
/// - Rays that merely graze a surface may or may not hit (measure zero).
/// - A zero or non-finite direction, or a non-finite origin: no hit. No NaN
///   is ever returned.
///
/// Interiors are computed as a parametric interval `[near, far]` (slabs for
/// boxes and caps, a numerically stable quadratic for round shapes: the
/// discriminant is formed from the closest-approach distance, not from
/// `b^2 - 4ac`, so a 0.1 m trunk at 40 m keeps its precision in float).
///
/// All functions are pure, allocation-free and thread-safe.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace streamclust::sim {

/// An axis-aligned bounding box; empty when `lo > hi` on any axis.
struct Aabb {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
  Eigen::Vector3f hi = Eigen::Vector3f::Constant(-std::numeric_limits<float>::infinity());

  bool empty() const { return (lo.array() > hi.array()).any(); }
  void extend(const Eigen::Vector3f& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void extend(const Aabb& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  Aabb translated(const Eigen::Vector3f& v) const { return Aabb{lo + v, hi + v}; }
  Eigen::Vector3f center() const { return 0.5f * (lo + hi); }
  bool intersects(const Aabb& b) const { return (lo.array() <= b.hi.array()).all() && (b.lo.array() <= hi.array()).all(); }
};

/// A plane `normal . x = offset`, optionally bounded to a rectangle.
/// Two-sided. Build with `Plane::infinite` or `Plane::rectangle`.
struct Plane {
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();  ///< unit normal
  float offset = 0.0f;                                ///< normal . x on the plane [m]
  bool bounded = false;                               ///< true: only the rectangle below
  Eigen::Vector3f center = Eigen::Vector3f::Zero();   ///< rectangle center [m]
  Eigen::Vector3f u_axis = Eigen::Vector3f::UnitX();  ///< unit, in the plane
  Eigen::Vector3f v_axis = Eigen::Vector3f::UnitY();  ///< unit, in the plane, orthogonal to u
  float half_u = 0.0f;                                ///< rectangle half extent along u [m]
  float half_v = 0.0f;                                ///< rectangle half extent along v [m]

  /// The infinite plane through `point` with normal `normal` (normalized here).
  static Plane infinite(const Eigen::Vector3f& normal, const Eigen::Vector3f& point) {
    Plane p;
    p.normal = normal.normalized();
    p.offset = p.normal.dot(point);
    return p;
  }
  /// The rectangle `center + a*u + b*v`, |a| <= half_u, |b| <= half_v; u and v
  /// are normalized here and v is made orthogonal to u.
  static Plane rectangle(const Eigen::Vector3f& center, const Eigen::Vector3f& u, const Eigen::Vector3f& v, float half_u,
                         float half_v) {
    Plane p;
    p.u_axis = u.normalized();
    p.v_axis = (v - v.dot(p.u_axis) * p.u_axis).normalized();
    const Eigen::Vector3f& a = p.u_axis;  // a x b by hand: cross() needs <Eigen/Geometry>
    const Eigen::Vector3f& b = p.v_axis;
    p.normal = Eigen::Vector3f(a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x());
    p.offset = p.normal.dot(center);
    p.bounded = true;
    p.center = center;
    p.half_u = half_u;
    p.half_v = half_v;
    return p;
  }
  /// Bounds of the rectangle (empty box for an infinite plane: it has none).
  Aabb bounds() const {
    Aabb b;
    if (!bounded) return b;
    for (float su : {-1.0f, 1.0f})
      for (float sv : {-1.0f, 1.0f}) b.extend(center + su * half_u * u_axis + sv * half_v * v_axis);
    return b;
  }
};

/// A box of half extents `half` around `center`, rotated by `yaw` [rad]
/// about the vertical (z) axis. `Box::aligned(lo, hi)` for yaw 0.
struct Box {
  Eigen::Vector3f center = Eigen::Vector3f::Zero();
  Eigen::Vector3f half = Eigen::Vector3f::Constant(0.5f);  ///< half extents along the box axes [m]
  float cos_yaw = 1.0f;                                    ///< cached cos(yaw)
  float sin_yaw = 0.0f;                                    ///< cached sin(yaw)

  static Box aligned(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) {
    Box b;
    b.center = 0.5f * (lo + hi);
    b.half = 0.5f * (hi - lo).cwiseAbs();
    return b;
  }
  static Box rotated(const Eigen::Vector3f& center, const Eigen::Vector3f& half, float yaw) {
    Box b;
    b.center = center;
    b.half = half.cwiseAbs();
    b.cos_yaw = std::cos(yaw);
    b.sin_yaw = std::sin(yaw);
    return b;
  }
  Aabb bounds() const {
    const float ex = std::abs(cos_yaw) * half.x() + std::abs(sin_yaw) * half.y();
    const float ey = std::abs(sin_yaw) * half.x() + std::abs(cos_yaw) * half.y();
    const Eigen::Vector3f e(ex, ey, half.z());
    return Aabb{center - e, center + e};
  }
};

/// A vertical cylinder, capped at `z_min` and `z_max`.
struct Cylinder {
  float x = 0.0f;  ///< axis position [m]
  float y = 0.0f;
  float radius = 0.5f;
  float z_min = 0.0f;
  float z_max = 1.0f;
  Aabb bounds() const {
    return Aabb{Eigen::Vector3f(x - radius, y - radius, z_min), Eigen::Vector3f(x + radius, y + radius, z_max)};
  }
};

/// A sphere.
struct Sphere {
  Eigen::Vector3f center = Eigen::Vector3f::Zero();
  float radius = 0.5f;
  Aabb bounds() const {
    return Aabb{center - Eigen::Vector3f::Constant(radius), center + Eigen::Vector3f::Constant(radius)};
  }
};

/// An axis-aligned ellipsoid with semi-axes `radii` (all > 0).
struct Ellipsoid {
  Eigen::Vector3f center = Eigen::Vector3f::Zero();
  Eigen::Vector3f radii = Eigen::Vector3f::Constant(0.5f);
  Aabb bounds() const { return Aabb{center - radii, center + radii}; }
};

/// A vertical capsule: the points within `radius` of the segment from
/// (x, y, z_low) to (x, y, z_high). It spans z_low - radius .. z_high + radius.
struct Capsule {
  float x = 0.0f;
  float y = 0.0f;
  float radius = 0.3f;
  float z_low = 0.3f;   ///< lower segment end (center of the bottom hemisphere) [m]
  float z_high = 1.4f;  ///< upper segment end (center of the top hemisphere) [m]

  /// A capsule standing on `z_ground` with total height `height` (>= 2 radius).
  static Capsule standing(float x, float y, float z_ground, float height, float radius) {
    Capsule c;
    c.x = x;
    c.y = y;
    c.radius = radius;
    c.z_low = z_ground + radius;
    c.z_high = std::max(c.z_low, z_ground + height - radius);
    return c;
  }
  Aabb bounds() const {
    return Aabb{Eigen::Vector3f(x - radius, y - radius, z_low - radius),
                Eigen::Vector3f(x + radius, y + radius, z_high + radius)};
  }
};

namespace detail {

/// Directions with a component below this magnitude are treated as parallel
/// to the corresponding axis / plane.
inline constexpr float kParallelEpsilon = 1e-12f;

/// The parametric interval where a ray is inside a convex solid.
struct Interval {
  float near = -std::numeric_limits<float>::infinity();
  float far = std::numeric_limits<float>::infinity();
  bool valid = true;

  void clip(float a, float b) {
    near = std::max(near, a);
    far = std::min(far, b);
    if (!(near <= far)) valid = false;
  }
};

inline Interval empty_interval() {
  Interval i;
  i.valid = false;
  return i;
}

/// The entry distance of a ray that starts outside; nothing when the
/// interval is empty, behind the origin, or contains the origin.
inline std::optional<float> entry(const Interval& i) {
  if (!i.valid || !(i.near > 0.0f) || !(i.near < std::numeric_limits<float>::infinity())) return std::nullopt;
  return i.near;
}

/// Slab `lo <= o + t d <= hi` along one axis.
inline void clip_slab(Interval& i, float o, float d, float lo, float hi) {
  if (!i.valid) return;
  if (std::abs(d) < kParallelEpsilon) {
    if (o < lo || o > hi) i.valid = false;
    return;
  }
  const float inv = 1.0f / d;
  float t0 = (lo - o) * inv;
  float t1 = (hi - o) * inv;
  if (t0 > t1) std::swap(t0, t1);
  i.clip(t0, t1);
}

/// Interval inside the sphere of radius r around the origin, for a ray with
/// origin `oc` relative to the center. Stable: h^2 = r^2 - |closest point|^2.
template <int N>
inline Interval ball_interval(const Eigen::Matrix<float, N, 1>& oc, const Eigen::Matrix<float, N, 1>& d, float r) {
  const float a = d.squaredNorm();
  if (a < kParallelEpsilon * kParallelEpsilon) {
    // Degenerate (e.g. a vertical ray against a vertical axis): inside for all t or never.
    if (oc.squaredNorm() <= r * r) return Interval{};
    return empty_interval();
  }
  const float tc = -oc.dot(d) / a;
  const Eigen::Matrix<float, N, 1> closest = oc + tc * d;
  const float h2 = r * r - closest.squaredNorm();
  if (h2 < 0.0f) return empty_interval();
  const float s = std::sqrt(h2 / a);
  return Interval{tc - s, tc + s, true};
}

inline bool finite_ray(const Eigen::Vector3f& o, const Eigen::Vector3f& d) {
  return o.allFinite() && d.allFinite() && d.squaredNorm() > kParallelEpsilon * kParallelEpsilon;
}

inline Interval interval(const Box& b, const Eigen::Vector3f& o, const Eigen::Vector3f& d) {
  const Eigen::Vector3f r = o - b.center;
  // Rotate into the box frame by -yaw.
  const float ox = b.cos_yaw * r.x() + b.sin_yaw * r.y();
  const float oy = -b.sin_yaw * r.x() + b.cos_yaw * r.y();
  const float dx = b.cos_yaw * d.x() + b.sin_yaw * d.y();
  const float dy = -b.sin_yaw * d.x() + b.cos_yaw * d.y();
  Interval i;
  clip_slab(i, ox, dx, -b.half.x(), b.half.x());
  clip_slab(i, oy, dy, -b.half.y(), b.half.y());
  clip_slab(i, r.z(), d.z(), -b.half.z(), b.half.z());
  return i;
}

inline Interval interval(const Cylinder& c, const Eigen::Vector3f& o, const Eigen::Vector3f& d) {
  Interval i = ball_interval<2>(Eigen::Vector2f(o.x() - c.x, o.y() - c.y), Eigen::Vector2f(d.x(), d.y()), c.radius);
  clip_slab(i, o.z(), d.z(), c.z_min, c.z_max);
  return i;
}

inline Interval interval(const Sphere& s, const Eigen::Vector3f& o, const Eigen::Vector3f& d) {
  return ball_interval<3>(Eigen::Vector3f(o - s.center), d, s.radius);
}

inline Interval interval(const Ellipsoid& e, const Eigen::Vector3f& o, const Eigen::Vector3f& d) {
  // Scale space so the ellipsoid becomes the unit sphere; t is unchanged.
  const Eigen::Vector3f inv = e.radii.cwiseInverse();
  return ball_interval<3>(Eigen::Vector3f((o - e.center).cwiseProduct(inv)), Eigen::Vector3f(d.cwiseProduct(inv)), 1.0f);
}

inline Interval interval(const Capsule& c, const Eigen::Vector3f& o, const Eigen::Vector3f& d) {
  // Convex union of a capped cylinder and two spheres: along a ray the union
  // of their intervals is one interval [min near, max far].
  const Cylinder body{c.x, c.y, c.radius, c.z_low, c.z_high};
  const Interval parts[3] = {interval(body, o, d),
                             ball_interval<3>(Eigen::Vector3f(o.x() - c.x, o.y() - c.y, o.z() - c.z_low), d, c.radius),
                             ball_interval<3>(Eigen::Vector3f(o.x() - c.x, o.y() - c.y, o.z() - c.z_high), d, c.radius)};
  Interval u = empty_interval();
  for (const Interval& p : parts) {
    if (!p.valid) continue;
    if (!u.valid) {
      u = p;
    } else {
      u.near = std::min(u.near, p.near);
      u.far = std::max(u.far, p.far);
    }
  }
  return u;
}

/// Ray against a slab-inflated AABB: true when the ray meets the box within
/// (0, t_max]. `inv_d` is the componentwise inverse direction with zero
/// components replaced by a huge finite value (see `safe_inverse`).
inline bool ray_hits_aabb(const Aabb& b, const Eigen::Vector3f& o, const Eigen::Vector3f& inv_d, float t_max) {
  const Eigen::Array3f t0 = (b.lo - o).array() * inv_d.array();
  const Eigen::Array3f t1 = (b.hi - o).array() * inv_d.array();
  const float near = t0.min(t1).maxCoeff();
  const float far = t0.max(t1).minCoeff();
  return near <= far && far >= 0.0f && near <= t_max;
}

/// Componentwise 1/d with |d| < 1e-20 replaced by +-1e20 (finite, so that
/// products with a zero numerator stay 0 rather than NaN).
inline Eigen::Vector3f safe_inverse(const Eigen::Vector3f& d) {
  Eigen::Vector3f inv;
  for (int k = 0; k < 3; ++k) {
    const float c = d[k];
    inv[k] = std::abs(c) < 1e-20f ? (std::signbit(c) ? -1e20f : 1e20f) : 1.0f / c;
  }
  return inv;
}

}  // namespace detail

/// Ray-plane intersection; see the file comment for conventions. O(1).
inline std::optional<float> intersect(const Plane& p, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) {
  if (!detail::finite_ray(origin, direction)) return std::nullopt;
  const float denom = p.normal.dot(direction);
  if (std::abs(denom) < detail::kParallelEpsilon) return std::nullopt;
  const float t = (p.offset - p.normal.dot(origin)) / denom;
  if (!(t > 0.0f) || !std::isfinite(t)) return std::nullopt;
  if (p.bounded) {
    const Eigen::Vector3f q = origin + t * direction - p.center;
    if (std::abs(q.dot(p.u_axis)) > p.half_u || std::abs(q.dot(p.v_axis)) > p.half_v) return std::nullopt;
  }
  return t;
}

/// Ray-box intersection (slabs in the box frame). O(1).
inline std::optional<float> intersect(const Box& b, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) {
  if (!detail::finite_ray(origin, direction)) return std::nullopt;
  return detail::entry(detail::interval(b, origin, direction));
}

/// Ray-cylinder intersection (side and both caps). O(1).
inline std::optional<float> intersect(const Cylinder& c, const Eigen::Vector3f& origin,
                                      const Eigen::Vector3f& direction) {
  if (!detail::finite_ray(origin, direction)) return std::nullopt;
  return detail::entry(detail::interval(c, origin, direction));
}

/// Ray-sphere intersection. O(1).
inline std::optional<float> intersect(const Sphere& s, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) {
  if (!detail::finite_ray(origin, direction)) return std::nullopt;
  return detail::entry(detail::interval(s, origin, direction));
}

/// Ray-ellipsoid intersection. O(1).
inline std::optional<float> intersect(const Ellipsoid& e, const Eigen::Vector3f& origin,
                                      const Eigen::Vector3f& direction) {
  if (!detail::finite_ray(origin, direction)) return std::nullopt;
  return detail::entry(detail::interval(e, origin, direction));
}

/// Ray-capsule intersection. O(1).
inline std::optional<float> intersect(const Capsule& c, const Eigen::Vector3f& origin,
                                      const Eigen::Vector3f& direction) {
  if (!detail::finite_ray(origin, direction)) return std::nullopt;
  return detail::entry(detail::interval(c, origin, direction));
}

/// Unit surface normals at a point on (or within float rounding of) a
/// primitive's surface, for the simulator's incidence angle: `normal_at(shape,
/// point)`. The side is unspecified (the simulator uses |n . d|). A box
/// takes the face the point is closest to in units of its half extents, a
/// cylinder its side or the nearer cap, a capsule the direction from its
/// axis segment. O(1), pure.
inline Eigen::Vector3f normal_at(const Plane& p, const Eigen::Vector3f& /*point*/) { return p.normal; }

inline Eigen::Vector3f normal_at(const Box& b, const Eigen::Vector3f& point) {
  const Eigen::Vector3f r = point - b.center;
  const Eigen::Vector3f q(b.cos_yaw * r.x() + b.sin_yaw * r.y(), -b.sin_yaw * r.x() + b.cos_yaw * r.y(), r.z());
  int axis = 0;
  float best = -1.0f;
  for (int k = 0; k < 3; ++k) {
    const float f = b.half[k] > 0.0f ? std::abs(q[k]) / b.half[k] : std::numeric_limits<float>::infinity();
    if (f > best) {
      best = f;
      axis = k;
    }
  }
  if (axis == 2) return Eigen::Vector3f::UnitZ();
  const float nx = axis == 0 ? 1.0f : 0.0f;
  const float ny = axis == 1 ? 1.0f : 0.0f;
  return Eigen::Vector3f(b.cos_yaw * nx - b.sin_yaw * ny, b.sin_yaw * nx + b.cos_yaw * ny, 0.0f);
}

inline Eigen::Vector3f normal_at(const Cylinder& c, const Eigen::Vector3f& point) {
  const Eigen::Vector2f radial(point.x() - c.x, point.y() - c.y);
  const float side = std::abs(radial.norm() - c.radius);
  const float cap = std::min(std::abs(point.z() - c.z_min), std::abs(point.z() - c.z_max));
  if (cap < side || !(radial.squaredNorm() > 0.0f)) return Eigen::Vector3f::UnitZ();
  const Eigen::Vector2f n = radial.normalized();
  return Eigen::Vector3f(n.x(), n.y(), 0.0f);
}

inline Eigen::Vector3f normal_at(const Sphere& s, const Eigen::Vector3f& point) {
  const Eigen::Vector3f r = point - s.center;
  return r.squaredNorm() > 0.0f ? Eigen::Vector3f(r.normalized()) : Eigen::Vector3f::UnitZ();
}

inline Eigen::Vector3f normal_at(const Ellipsoid& e, const Eigen::Vector3f& point) {
  const Eigen::Vector3f g = (point - e.center).cwiseQuotient(e.radii.cwiseProduct(e.radii));  // gradient / 2
  return g.squaredNorm() > 0.0f ? Eigen::Vector3f(g.normalized()) : Eigen::Vector3f::UnitZ();
}

inline Eigen::Vector3f normal_at(const Capsule& c, const Eigen::Vector3f& point) {
  const Eigen::Vector3f axis_point(c.x, c.y, std::clamp(point.z(), c.z_low, c.z_high));
  const Eigen::Vector3f r = point - axis_point;
  return r.squaredNorm() > 0.0f ? Eigen::Vector3f(r.normalized()) : Eigen::Vector3f::UnitZ();
}

}  // namespace streamclust::sim
