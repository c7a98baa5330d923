// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Trajectory: the path a moving object of a scene follows (periodic at
/// constant speed along a closed polyline or a horizontal circle, or once
/// along an open polyline from standing), and ObjectPose, its position and
/// heading at one time.

#include <streamclust/sim/shapes.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace streamclust::sim {

/// Position and heading of a moving object at one time.
struct ObjectPose {
  Eigen::Vector3f position = Eigen::Vector3f::Zero();  ///< world [m]
  float cos_yaw = 1.0f;                                ///< heading (direction of motion) about +z
  float sin_yaw = 0.0f;
};

/// A path: periodic at constant speed along a closed polyline (a segment
/// travelled back and forth is the polyline a -> b -> a, with an
/// instantaneous turn at each end) or a horizontal circle; or once along an
/// open polyline, standing until a start time, then accelerating to a top
/// speed (`depart`). Headings turn instantaneously at the polyline's corners.
class Trajectory {
 public:
  /// Standing still at `p` (heading +x).
  static Trajectory fixed(const Eigen::Vector3f& p) { return loop({p}, 0.0f); }

  /// From `a` to `b` and back at `speed` [m/s]; `phase` [m] is the distance
  /// already travelled along a -> b -> a at t = 0 (any value, wrapped).
  static Trajectory back_and_forth(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float speed, float phase = 0.0f) {
    return loop({a, b}, speed, phase);
  }

  /// Around the closed polyline `points` (last joined to first) at `speed`
  /// [m/s], starting `phase` [m] along it at t = 0.
  static Trajectory loop(std::vector<Eigen::Vector3f> points, float speed, float phase = 0.0f) {
    if (points.empty()) throw std::invalid_argument("Trajectory::loop: points must not be empty");
    Trajectory t = polyline_path(std::move(points), true);
    t.kind_ = Kind::polyline;
    t.speed_ = speed;
    t.phase_ = phase;
    return t;
  }

  /// Once along the open polyline `points` (at least two): standing at the
  /// first point until `start` [s], then accelerating at `acceleration`
  /// [m/s^2] up to `top_speed` [m/s], standing at the last point once there.
  /// A car pulling out of a parking space, say.
  static Trajectory depart(std::vector<Eigen::Vector3f> points, double start, float top_speed, float acceleration) {
    if (points.size() < 2) throw std::invalid_argument("Trajectory::depart: an open path needs at least two points");
    if (!(top_speed > 0.0f) || !(acceleration > 0.0f)) {
      throw std::invalid_argument("Trajectory::depart: top_speed and acceleration must be > 0");
    }
    Trajectory t = polyline_path(std::move(points));
    t.kind_ = Kind::departure;
    t.start_ = start;
    t.speed_ = top_speed;
    t.acceleration_ = acceleration;
    return t;
  }

  /// Around the horizontal circle of `radius` about `center` at `speed`
  /// [m/s] (> 0 counter-clockwise seen from above), starting at angle
  /// `phase` [rad] (0: center + radius * x).
  static Trajectory circle(const Eigen::Vector3f& center, float radius, float speed, float phase = 0.0f) {
    Trajectory t;
    t.kind_ = Kind::circle;
    t.points_ = {center};
    t.radius_ = std::abs(radius);
    t.speed_ = speed;
    t.phase_ = phase;
    return t;
  }

  /// Pose at stream time `time` [s]. O(number of polyline points).
  ObjectPose pose(double time) const {
    ObjectPose p;
    if (kind_ == Kind::circle) {
      constexpr double kTwoPi = 6.283185307179586476925;
      double angle = static_cast<double>(phase_);
      if (radius_ > 0.0f) angle += static_cast<double>(speed_) * time / static_cast<double>(radius_);
      angle -= kTwoPi * std::floor(angle / kTwoPi);
      const float c = static_cast<float>(std::cos(angle));
      const float s = static_cast<float>(std::sin(angle));
      p.position = points_[0] + radius_ * Eigen::Vector3f(c, s, 0.0f);
      p.cos_yaw = speed_ >= 0.0f ? -s : s;
      p.sin_yaw = speed_ >= 0.0f ? c : -c;
      return p;
    }
    const double total = cumulative_.back();
    if (!(total > 1e-9)) {
      p.position = points_[0];
      return p;
    }
    if (kind_ == Kind::departure) return along(std::min(distance_departed(time), total), 1.0f);
    double s = static_cast<double>(phase_) + static_cast<double>(speed_) * time;
    s -= total * std::floor(s / total);
    return along(s, speed_ >= 0.0f ? 1.0f : -1.0f);
  }

  Eigen::Vector3f position(double time) const { return pose(time).position; }

  /// Bounds of every position the trajectory takes.
  /// An open path's bounds are its points' (the segments lie between them).
  Aabb swept_bounds() const {
    Aabb b;
    if (kind_ == Kind::circle) {
      const Eigen::Vector3f r(radius_, radius_, 0.0f);
      return Aabb{points_[0] - r, points_[0] + r};
    }
    for (const Eigen::Vector3f& p : points_) b.extend(p);
    return b;
  }

  /// Time for one full period [s] (infinity when standing still or along
  /// an open path).
  double period() const {
    if (kind_ == Kind::departure) return std::numeric_limits<double>::infinity();
    constexpr double kTwoPi = 6.283185307179586476925;
    const double length = kind_ == Kind::circle ? kTwoPi * static_cast<double>(radius_) : cumulative_.back();
    if (speed_ == 0.0f || !(length > 0.0)) return std::numeric_limits<double>::infinity();
    return length / std::abs(static_cast<double>(speed_));
  }

 private:
  enum class Kind { polyline, circle, departure };
  Trajectory() = default;

  /// Cumulative lengths and headings of the segments between consecutive
  /// `points` (closed: the last joined to the first as well).
  static Trajectory polyline_path(std::vector<Eigen::Vector3f> points, bool closed = false) {
    Trajectory t;
    t.points_ = std::move(points);
    const std::size_t n = t.points_.size();
    const std::size_t segments = closed ? n : n - 1;
    t.cumulative_.assign(segments + 1, 0.0);
    for (std::size_t i = 0; i < segments; ++i) {
      const Eigen::Vector3f seg = t.points_[(i + 1) % n] - t.points_[i];
      t.cumulative_[i + 1] = t.cumulative_[i] + static_cast<double>(seg.norm());
      const Eigen::Vector2f h(seg.x(), seg.y());
      const float len = h.norm();
      t.headings_.push_back(len > 1e-6f ? Eigen::Vector2f(h / len) : Eigen::Vector2f(1.0f, 0.0f));
    }
    return t;
  }

  /// Distance along a departure's path at `time` [s]: 0 before the start,
  /// a t^2 / 2 while accelerating, then the top speed. Unbounded.
  double distance_departed(double time) const {
    const double t = time - start_;
    if (t <= 0.0) return 0.0;
    const double a = static_cast<double>(acceleration_);
    const double v = static_cast<double>(speed_);
    const double t_top = v / a;
    return t <= t_top ? 0.5 * a * t * t : 0.5 * v * t_top + v * (t - t_top);
  }

  /// Pose `s` [m] along the polyline, 0 <= s <= its length; `sign` -1
  /// faces backwards (a negative speed).
  ObjectPose along(double s, float sign) const {
    ObjectPose p;
    std::size_t i = 0;
    const std::size_t segments = headings_.size();
    while (i + 1 < segments && s >= cumulative_[i + 1]) ++i;
    const double len = cumulative_[i + 1] - cumulative_[i];
    const float f = len > 1e-12 ? static_cast<float>((s - cumulative_[i]) / len) : 0.0f;
    const Eigen::Vector3f& a = points_[i];
    const Eigen::Vector3f& b = points_[(i + 1) % points_.size()];
    p.position = a + f * (b - a);
    p.cos_yaw = sign * headings_[i].x();
    p.sin_yaw = sign * headings_[i].y();
    return p;
  }

  Kind kind_ = Kind::polyline;
  std::vector<Eigen::Vector3f> points_;
  std::vector<double> cumulative_;
  std::vector<Eigen::Vector2f> headings_;
  float radius_ = 0.0f;
  float speed_ = 0.0f;
  float phase_ = 0.0f;
  double start_ = 0.0;         ///< departure: when it sets off [s]
  float acceleration_ = 0.0f;  ///< departure [m/s^2]
};

}  // namespace streamclust::sim
