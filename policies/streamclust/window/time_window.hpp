// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// TimeWindow: the sliding window holds the last T_B seconds of points.

#include <streamclust/concepts/window.hpp>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace streamclust {

/// Sliding window of fixed duration T_B (C-ARC's buffer time): the oldest
/// point leaves once `newest - oldest > duration`, so the window spans at
/// most `duration` seconds (points exactly `duration` apart stay together).
/// The window is complete (calibration may end) once `newest - oldest >=
/// duration`. The point count is unbounded (it follows the sensor rate).
///
/// duration = 0 keeps only points with the newest timestamp.
/// O(1). Thread safety: immutable; const and thread-safe.
///
/// Usage:
/// \code
///   streamclust::TimeWindow window{{0.5}};  // T_B = 0.5 s
///   window.expired(0.0, 0.6, 1000);         // true: the point at t = 0 leaves
/// \endcode
class TimeWindow {
 public:
  struct Params {
    double duration = 0.1;  ///< [s] T_B, finite, >= 0
  };

  /// Throws std::invalid_argument unless duration is finite and >= 0.
  explicit TimeWindow(const Params& params) : params_(params) {
    if (!std::isfinite(params.duration) || params.duration < 0.0) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.9g", params.duration);
      throw std::invalid_argument(std::string("TimeWindow: parameter duration = ") + buf +
                                  " is invalid; allowed: finite, >= 0 s");
    }
  }

  /// The oldest point (time `oldest` [s]) must leave when the newest is at
  /// `newest` [s]: newest - oldest > duration. `size` is ignored. O(1).
  bool expired(double oldest, double newest, std::size_t /*size*/) const {
    return newest - oldest > params_.duration;
  }

  /// The window spans its full duration: newest - oldest >= duration. O(1).
  bool complete(double oldest, double newest, std::size_t /*size*/) const {
    return newest - oldest >= params_.duration;
  }

  const Params& params() const { return params_; }

 private:
  Params params_;
};

}  // namespace streamclust

static_assert(streamclust::is_window_policy_v<streamclust::TimeWindow>,
              "STREAMCLUST_WINDOW_POLICY_INVALID: TimeWindow");
