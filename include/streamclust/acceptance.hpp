// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The one rule that decides whether an offered point is clustered, shared
/// by the engine, the batch clusterer and the tools, so that the same point
/// is counted under the same reason everywhere.

#include <streamclust/types.hpp>

#include <cmath>

namespace streamclust {

/// Why a projected point is not accepted, in this order: a non-finite
/// coordinate or time (`non_finite`), then the projection's range and field
/// of view checks (`too_close`, `outside_fov`); `accepted` otherwise. The
/// time order is StreamTimeOrder's. O(1), pure.
inline RejectReason judge_point(const Projected& projected, double time) {
  if (projected.reason == RejectReason::non_finite || !std::isfinite(time)) return RejectReason::non_finite;
  return projected.reason;
}

/// Stream time must not go backwards: a point earlier than the last accepted
/// one is rejected (`time_backwards`). Equal times are fine.
/// O(1). Thread safety: none.
class StreamTimeOrder {
 public:
  /// judge_point, then the time order: the full reason for a point at
  /// `time` [s] (accept() it when the result is `accepted`).
  RejectReason judge(const Projected& projected, double time) const {
    const RejectReason r = judge_point(projected, time);
    if (r == RejectReason::accepted && seen_ && time < last_) return RejectReason::time_backwards;
    return r;
  }
  /// Records an accepted point's (finite) time.
  void accept(double time) {
    seen_ = true;
    last_ = time;
  }
  /// A time `time` [s] may move the stream on (advance_to): finite and not
  /// before the last accepted time.
  bool may_advance_to(double time) const { return std::isfinite(time) && !(seen_ && time < last_); }
  bool seen() const { return seen_; }
  /// The last accepted time [s] (0 before any).
  double last() const { return last_; }

 private:
  bool seen_ = false;
  double last_ = 0.0;
};

}  // namespace streamclust
