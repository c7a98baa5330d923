// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The grid a clusterer uses, from its resolution policy and projection:
/// one rule for the engine, the batch clusterer and the tools.

#include <streamclust/types.hpp>

#include <vector>

namespace streamclust {

/// The grid of `size` for `projection`: columns wrap when its horizontal
/// field of view is a full turn; an empty size (a calibration that saw no
/// point) becomes one cell. O(1).
template <class Projection>
GridShape grid_shape_for(GridSize size, const Projection& projection) {
  if (size.rows == 0 || size.cols == 0) size = GridSize{1, 1};
  return GridShape{size.rows, size.cols, projection.wraps_horizontally()};
}

/// The grid chosen by `resolution`: its fixed grid, or, for a calibrating
/// policy, its choice on the projections of the first window's accepted
/// points (`first_window`, in stream order). The first window is what the
/// engine buffers: the accepted points before the first one that completes
/// it (`window.complete(time of the first, time of the new point, points
/// buffered + 1)`, e.g. at or after T_B for a time window); FirstWindow
/// collects it. Cost: the policy's.
template <class Resolution, class Projection>
GridShape choose_grid(Resolution& resolution, const Projection& projection, const std::vector<Projected>& first_window) {
  if (!resolution.needs_calibration()) return grid_shape_for(resolution.grid(), projection);
  return grid_shape_for(resolution.calibrate(first_window, projection.fov_aspect()), projection);
}

/// Collects the first window of a stream of accepted points, as the engine
/// buffers it for calibration: `offer(projected, time)` returns true at the
/// first point that completes the window (that point is not part of it).
/// O(1) per point. Thread safety: none.
template <class Window>
class FirstWindow {
 public:
  explicit FirstWindow(const Window& window) : window_(window) {}
  /// Offers an accepted point at `time` [s]; true once the window is complete.
  bool offer(const Projected& projected, double time) {
    if (complete_) return true;
    if (!points_.empty() && window_.complete(first_time_, time, points_.size() + 1)) return complete_ = true;
    if (points_.empty()) first_time_ = time;
    points_.push_back(projected);
    return false;
  }
  bool complete() const { return complete_; }
  /// The window's projections, in stream order.
  const std::vector<Projected>& points() const { return points_; }

 private:
  const Window& window_;
  std::vector<Projected> points_;
  double first_time_ = 0.0;
  bool complete_ = false;
};

}  // namespace streamclust
