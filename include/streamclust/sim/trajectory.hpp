// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Trajectory: the periodic path a moving object of a scene follows at
/// constant speed (a closed polyline or a horizontal circle), and
/// ObjectPose, its position and heading at one time.

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

/// A periodic path followed at constant speed: a closed polyline (a segment
/// travelled back and forth is the polyline a -> b -> a, with an
/// instantaneous turn at each end) or a horizontal circle.
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
    Trajectory t;
    t.kind_ = Kind::polyline;
    t.points_ = std::move(points);
    t.speed_ = speed;
    t.phase_ = phase;
    const std::size_t n = t.points_.size();
    t.cumulative_.assign(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3f seg = t.points_[(i + 1) % n] - t.points_[i];
      t.cumulative_[i + 1] = t.cumulative_[i] + static_cast<double>(seg.norm());
      const Eigen::Vector2f h(seg.x(), seg.y());
      const float len = h.norm();
      t.headings_.push_back(len > 1e-6f ? Eigen::Vector2f(h / len) : Eigen::Vector2f(1.0f, 0.0f));
    }
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
    double s = static_cast<double>(phase_) + static_cast<double>(speed_) * time;
    s -= total * std::floor(s / total);
    std::size_t i = 0;
    const std::size_t n = points_.size();
    while (i + 1 < n && s >= cumulative_[i + 1]) ++i;
    const double len = cumulative_[i + 1] - cumulative_[i];
    const float f = len > 1e-12 ? static_cast<float>((s - cumulative_[i]) / len) : 0.0f;
    const Eigen::Vector3f& a = points_[i];
    const Eigen::Vector3f& b = points_[(i + 1) % n];
    p.position = a + f * (b - a);
    const float sign = speed_ >= 0.0f ? 1.0f : -1.0f;
    p.cos_yaw = sign * headings_[i].x();
    p.sin_yaw = sign * headings_[i].y();
    return p;
  }

  Eigen::Vector3f position(double time) const { return pose(time).position; }

  /// Bounds of every position the trajectory takes.
  Aabb swept_bounds() const {
    Aabb b;
    if (kind_ == Kind::circle) {
      const Eigen::Vector3f r(radius_, radius_, 0.0f);
      return Aabb{points_[0] - r, points_[0] + r};
    }
    for (const Eigen::Vector3f& p : points_) b.extend(p);
    return b;
  }

  /// Time for one full period [s] (infinity when standing still).
  double period() const {
    constexpr double kTwoPi = 6.283185307179586476925;
    const double length = kind_ == Kind::circle ? kTwoPi * static_cast<double>(radius_) : cumulative_.back();
    if (speed_ == 0.0f || !(length > 0.0)) return std::numeric_limits<double>::infinity();
    return length / std::abs(static_cast<double>(speed_));
  }

 private:
  enum class Kind { polyline, circle };
  Trajectory() = default;

  Kind kind_ = Kind::polyline;
  std::vector<Eigen::Vector3f> points_;
  std::vector<double> cumulative_;
  std::vector<Eigen::Vector2f> headings_;
  float radius_ = 0.0f;
  float speed_ = 0.0f;
  float phase_ = 0.0f;
};

}  // namespace streamclust::sim
