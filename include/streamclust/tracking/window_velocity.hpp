// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// window_velocity: an object's horizontal velocity from one window, out of
/// its points' own capture times. The window spans T_B (0.5 s), so a
/// moving object's points are spread along its path; the centroids of time
/// slices, fitted against their times, give the velocity and its standard
/// error without a second retrieval.

#include <streamclust/detail/parameter_check.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {
namespace tracking {

/// Settings of window_velocity.
struct WindowVelocityParams {
  double slice_seconds = 0.1;     ///< [s] time slice of one centroid (a Mid-360 turn), (0, 10]
  std::size_t slice_points = 3;   ///< fewer points: the slice is left out, [1, 100000]
  std::size_t min_slices = 3;     ///< fewer usable slices: no measurement, [3, 1000]
  float min_error = 0.05f;        ///< [m/s] floor of the standard error (scan-pattern bias), [0, 10]

  /// Throws std::invalid_argument naming the first setting out of range.
  void validate() const {
    auto check = [](bool ok, const char* name, double value, const char* allowed) {
      streamclust::detail::require_parameter(ok, "WindowVelocityParams", name, value, allowed);
    };
    check(slice_seconds > 0.0 && slice_seconds <= 10.0, "slice_seconds", slice_seconds, "(0, 10] s");
    check(slice_points >= 1 && slice_points <= 100000, "slice_points", static_cast<double>(slice_points),
          "[1, 100000]");
    check(min_slices >= 3 && min_slices <= 1000, "min_slices", static_cast<double>(min_slices), "[3, 1000]");
    check(min_error >= 0.0f && min_error <= 10.0f, "min_error", min_error, "[0, 10] m/s");
  }
};

/// A velocity measured within one window.
struct WindowVelocity {
  bool valid = false;                                  ///< enough slices for a fit
  Eigen::Vector2f velocity = Eigen::Vector2f::Zero();  ///< [m/s] in the ground plane
  float error = 0.0f;  ///< [m/s] standard error of each component (at least min_error)
  std::size_t slices = 0;  ///< time slices fitted
  /// [m/s] the difference between the velocities of the object's two ends
  /// along `velocity` (each end the slices' extreme points, fitted as the
  /// centroids are): near zero for a moving object, about the speed for a
  /// standing one whose visible part shrinks or grows
  float end_difference = 0.0f;
};

/// Scratch storage of window_velocity, reused between calls.
struct WindowVelocityScratch {
  struct Slice {
    double sum_x = 0.0, sum_y = 0.0, sum_t = 0.0;
    std::size_t n = 0;
    double lo = std::numeric_limits<double>::infinity();  ///< [m] the slice's ends along the motion
    double hi = -std::numeric_limits<double>::infinity();
  };
  std::vector<Slice> slices;
};

/// The velocity of one object from its points `xyz` and their capture
/// times `t` [s] (same length): the points fall into slices of
/// `slice_seconds` from the oldest; each slice with `slice_points` gives a
/// centroid at its mean time, and a least-squares line through the
/// centroids (weighted by their points) gives the velocity. Its standard
/// error comes from the residuals (at least `min_error`: different parts of
/// an object show in different slices, a bias the residuals of a few slices
/// understate). The velocities of the slices' two ends along that motion,
/// fitted the same way, tell motion from a change of view
/// (WindowVelocity::end_difference): a moving object moves both ends; a
/// standing one whose visible part shrinks or grows (the field of view's
/// edge sweeping over it while the sensor turns, an occluder passing) moves
/// one end and its centroid, not the other. O(n + slices). Thread safety:
/// none on `scratch`.
inline WindowVelocity window_velocity(const std::vector<Eigen::Vector3f>& xyz, const std::vector<double>& t,
                                      const WindowVelocityParams& params, WindowVelocityScratch& scratch) {
  WindowVelocity out;
  if (xyz.size() != t.size()) throw std::invalid_argument("window_velocity: points and times differ in length");
  if (xyz.empty()) return out;
  const auto [lo, hi] = std::minmax_element(t.begin(), t.end());
  const double t0 = *lo;
  const auto count = static_cast<std::size_t>(std::floor((*hi - t0) / params.slice_seconds)) + 1;
  if (count < params.min_slices || count > 100000) return out;
  scratch.slices.assign(count, WindowVelocityScratch::Slice{});
  const Eigen::Vector3f origin = xyz.front();  // relative positions keep float precision far out
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    const auto k = std::min(count - 1, static_cast<std::size_t>((t[i] - t0) / params.slice_seconds));
    WindowVelocityScratch::Slice& s = scratch.slices[k];
    s.sum_x += static_cast<double>(xyz[i].x() - origin.x());
    s.sum_y += static_cast<double>(xyz[i].y() - origin.y());
    s.sum_t += t[i] - t0;
    ++s.n;
  }
  // Weighted least squares of the centroids against time, weight = points.
  double w = 0.0, wt = 0.0, wx = 0.0, wy = 0.0;
  std::size_t used = 0;
  for (const auto& s : scratch.slices) {
    if (s.n < params.slice_points) continue;
    const double n = static_cast<double>(s.n);
    w += n;
    wt += s.sum_t;
    wx += s.sum_x;
    wy += s.sum_y;
    ++used;
  }
  if (used < params.min_slices) return out;
  const double t_mean = wt / w, x_mean = wx / w, y_mean = wy / w;
  double stt = 0.0, stx = 0.0, sty = 0.0;
  for (const auto& s : scratch.slices) {
    if (s.n < params.slice_points) continue;
    const double n = static_cast<double>(s.n);
    const double dt = s.sum_t / n - t_mean;
    stt += n * dt * dt;
    stx += n * dt * (s.sum_x / n - x_mean);
    sty += n * dt * (s.sum_y / n - y_mean);
  }
  if (!(stt > 0.0)) return out;
  const double vx = stx / stt, vy = sty / stt;
  double residual = 0.0;
  for (const auto& s : scratch.slices) {
    if (s.n < params.slice_points) continue;
    const double n = static_cast<double>(s.n);
    const double dt = s.sum_t / n - t_mean;
    const double ex = s.sum_x / n - x_mean - vx * dt, ey = s.sum_y / n - y_mean - vy * dt;
    residual += n * (ex * ex + ey * ey);
  }
  // Weighted least squares: var(slope) = s^2 / stt, s^2 the weighted residual
  // per degree of freedom (used - 2), per component (x and y pooled).
  const double sigma2 = residual / (2.0 * static_cast<double>(used - 2));
  const double error = std::sqrt(sigma2 / stt);
  // The two ends: the slopes of the slices' extremes along the motion.
  double end_difference = 0.0;
  const double speed = std::hypot(vx, vy);
  if (speed > 0.0) {
    const double ux = vx / speed, uy = vy / speed;
    for (std::size_t i = 0; i < xyz.size(); ++i) {
      const auto k = std::min(count - 1, static_cast<std::size_t>((t[i] - t0) / params.slice_seconds));
      WindowVelocityScratch::Slice& s = scratch.slices[k];
      const double along = ux * static_cast<double>(xyz[i].x() - origin.x()) +
                           uy * static_cast<double>(xyz[i].y() - origin.y());
      s.lo = std::min(s.lo, along);
      s.hi = std::max(s.hi, along);
    }
    double slo = 0.0, shi = 0.0;  // sum of n dt end: the slope times stt (sum of n dt is 0)
    for (const auto& s : scratch.slices) {
      if (s.n < params.slice_points) continue;
      const double n = static_cast<double>(s.n);
      const double dt = s.sum_t / n - t_mean;
      slo += n * dt * s.lo;
      shi += n * dt * s.hi;
    }
    end_difference = std::fabs(shi - slo) / stt;
  }
  out.valid = true;
  out.velocity = Eigen::Vector2f(static_cast<float>(vx), static_cast<float>(vy));
  out.error = std::max(static_cast<float>(error), params.min_error);
  out.end_difference = static_cast<float>(end_difference);
  out.slices = used;
  return out;
}

}  // namespace tracking
}  // namespace streamclust
