// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// CountWindow: the sliding window holds the last N points.

#include <streamclust/concepts/window.hpp>

#include <cstddef>
#include <stdexcept>
#include <string>

namespace streamclust {

/// Sliding window of a fixed number of points: the oldest point leaves once
/// the count (including the point being inserted) exceeds `capacity`; the
/// window is complete once it holds `capacity` points. Memory and per-window
/// work are bounded whatever the sensor rate; the time span varies instead.
///
/// O(1). Thread safety: immutable; const and thread-safe.
///
/// Usage:
/// \code
///   streamclust::CountWindow window{{20000}};
///   window.expired(0.0, 1.0, 20001);  // true
/// \endcode
class CountWindow {
 public:
  struct Params {
    std::size_t capacity = 20000;  ///< [points], >= 1
  };

  /// Throws std::invalid_argument if capacity is 0.
  explicit CountWindow(const Params& params) : params_(params) {
    if (params.capacity < 1)
      throw std::invalid_argument("CountWindow: parameter capacity = " + std::to_string(params.capacity) +
                                  " is invalid; allowed: >= 1 points");
  }

  /// size > capacity (times ignored). O(1).
  bool expired(double /*oldest*/, double /*newest*/, std::size_t size) const { return size > params_.capacity; }

  /// size >= capacity (times ignored). O(1).
  bool complete(double /*oldest*/, double /*newest*/, std::size_t size) const { return size >= params_.capacity; }

  const Params& params() const { return params_; }

 private:
  Params params_;
};

}  // namespace streamclust

static_assert(streamclust::is_window_policy_v<streamclust::CountWindow>,
              "STREAMCLUST_WINDOW_POLICY_INVALID: CountWindow");
